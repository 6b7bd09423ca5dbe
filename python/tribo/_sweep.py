"""`sweep`: variants of a case run in parallel (threads: the solve releases the GIL) or on a
Dask distributed cluster, one DataFrame row per variant. A variant that fails is a row with
its error; the sweep goes on."""

import copy
import itertools
import os
import time
from concurrent.futures import ThreadPoolExecutor

import pandas as pd

from ._native import SolveError, TriboError
from ._result import load_case, run


def _split(address):
    return [int(k) if k.isdigit() else k for k in str(address).split(".")]


def set_value(case, address, value):
    """Sets `address` ("contact.0.friction", "force.0.fy", "mesh.size") in the case dict:
    numbers index arrays of tables, a missing key of a table is added."""
    keys = _split(address)
    node = case
    for depth, k in enumerate(keys):
        last = depth == len(keys) - 1
        where = ".".join(str(x) for x in keys[:depth]) or "the case"
        if isinstance(node, list):
            if not isinstance(k, int) or not -len(node) <= k < len(node):
                raise ValueError(
                    f"sweep parameter '{address}': {where} is an array of {len(node)} "
                    f"tables, '{k}' is not an index into it"
                )
        elif isinstance(node, dict):
            if isinstance(k, int):
                raise ValueError(
                    f"sweep parameter '{address}': {where} is a table, not an array"
                )
            if not last and k not in node:
                node[k] = {}
        else:
            raise ValueError(
                f"sweep parameter '{address}': {where} is a value, not a table or an array"
            )
        if last:
            node[k] = value
        else:
            node = node[k]


def variants(parameters):
    """The overrides of each variant: a dict of lists is a grid (every combination), a list
    of dicts gives the variants one by one."""
    if isinstance(parameters, dict):
        names = list(parameters)
        values = [list(parameters[n]) for n in names]
        return [dict(zip(names, combo)) for combo in itertools.product(*values)]
    if isinstance(parameters, (list, tuple)):
        out = []
        for i, v in enumerate(parameters):
            if not isinstance(v, dict):
                raise TypeError(
                    f"sweep: variant {i} is a {type(v).__name__}, expected a dict of overrides"
                )
            out.append(dict(v))
        return out
    raise TypeError(
        "sweep: parameters are a dict {address: [values]} (a grid) or a list of dicts"
    )


def _pair_columns(results):
    row = {}
    for i, c in enumerate(results["contact"], start=1):
        row[f"contact{i}_normal"] = c["normal_resultant"]
        row[f"contact{i}_tangential"] = c["tangential_resultant"]
        row[f"contact{i}_fx"] = c["force"][0]
        row[f"contact{i}_fy"] = c["force"][1]
    for g, r in results["reactions"].items():
        row[f"rx_{g}"] = r["rx"]
        row[f"ry_{g}"] = r["ry"]
    return row


def run_variant(case, base_dir, overrides, index, fields=None, threads=None):
    """One variant's row (a plain dict, so that it travels back from a Dask worker)."""
    row = {"variant": index, **overrides}
    t0 = time.perf_counter()
    try:
        c = copy.deepcopy(case)
        for address, value in overrides.items():
            set_value(c, address, value)
        r = run(c, base_dir=base_dir, threads=threads)
        row.update(status="converged", error=None)
        row["iterations"] = r.report["total_iterations"]
        row.update(r.probes)
        row.update(_pair_columns(r.results))
        if fields is not None:
            folder = os.path.join(fields, f"variant_{index:04d}")
            os.makedirs(folder, exist_ok=True)
            r.write_vtu(os.path.join(folder, "result.vtu"))
            if not r.history.empty:
                r.history.to_csv(os.path.join(folder, "history.csv"), index=False)
    except SolveError as e:
        row.update(status="failed", error=str(e))
    except (TriboError, ValueError, TypeError) as e:
        row.update(status="error", error=str(e))
    row["wall_s"] = time.perf_counter() - t0
    return row


def sweep(case, parameters, client=None, *, base_dir=None, fields=None, workers=None,
          threads=None):
    """Runs the variants of `case` (a path, TOML text or dict) given by `parameters` and
    returns one DataFrame row per variant: its parameters, `status` ("converged", "failed"
    for a failed solve, "error" for a case that cannot be run) and `error`, the Newton
    iterations, the probes, per contact pair the normal and tangential resultants and the
    total force (`contact1_normal`, ...), the reactions per support group, `wall_s`.

    client   a dask.distributed.Client: the variants run on its cluster (each worker needs
             tribo installed and the case's mesh file, if any, at the same path)
    workers  without a client, how many variants run at once (default: the CPU count)
    fields   a folder: each variant's result.vtu and history.csv in variant_NNNN/
    threads  threads per variant: default 1 when variants run side by side (on a cluster
             or with workers > 1: more would only contend for the cores), else all cores
    """
    if isinstance(case, dict):
        base = copy.deepcopy(case)
    else:
        base = load_case(case)
        if base_dir is None and isinstance(case, (str, os.PathLike)) and os.path.isfile(case):
            base_dir = os.path.dirname(os.path.abspath(case))
    base_dir = os.path.abspath(base_dir or os.getcwd())
    fields = os.path.abspath(os.fspath(fields)) if fields is not None else None
    todo = variants(parameters)
    # addresses checked before any work: a misspelt one is the sweep's error, not a row's
    for v in todo:
        for address, value in v.items():
            set_value(copy.deepcopy(base), address, value)
    n = workers or os.cpu_count() or 1
    side_by_side = client is not None or n > 1
    per_variant = threads if threads is not None else (1 if side_by_side else None)
    args = [(base, base_dir, v, i, fields, per_variant) for i, v in enumerate(todo)]
    if client is not None:
        futures = client.map(run_variant, *zip(*args), pure=False) if args else []
        rows = client.gather(futures)
    else:
        if n == 1:
            rows = [run_variant(*a) for a in args]
        else:
            with ThreadPoolExecutor(max_workers=n) as pool:
                rows = list(pool.map(lambda a: run_variant(*a), args))
    return pd.DataFrame(rows).set_index("variant")
