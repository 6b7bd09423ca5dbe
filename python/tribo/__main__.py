"""`python -m tribo sweep SWEEP.toml [--scheduler tcp://HOST:PORT] [-o OUT.csv]`: a sweep
described by a TOML file, run locally or on a Dask scheduler; the table is written as CSV.

SWEEP.toml:

    case = "c.toml"                 # relative to this file
    fields = "fields"               # optional: each variant's result.vtu and history.csv
    workers = 2                     # optional: variants at once without a scheduler
    [parameters]                    # a grid: every combination
    "contact.0.friction" = [0.1, 0.2, 0.3]
    # or one table per variant instead of [parameters]:
    # [[variant]]
    # "force.0.fy" = -8750.0
"""

import argparse
import os
import sys

from . import _native
from ._native import TriboError
from ._sweep import sweep

KEYS = {"case", "fields", "workers", "parameters", "variant"}


def _sweep(args):
    spec = _native.load_case(args.file, True, False)
    unknown = sorted(set(spec) - KEYS)
    if unknown:
        raise TriboError(f"{args.file}: unknown key(s) {unknown}; keys are {sorted(KEYS)}")
    if "case" not in spec:
        raise TriboError(f"{args.file}: 'case' (the case file to vary) is missing")
    if ("parameters" in spec) == ("variant" in spec):
        raise TriboError(f"{args.file}: give either [parameters] (a grid) or [[variant]] tables")
    here = os.path.dirname(os.path.abspath(args.file))
    case = os.path.join(here, spec["case"])
    fields = os.path.join(here, spec["fields"]) if "fields" in spec else None
    client = None
    if args.scheduler:
        from distributed import Client

        client = Client(args.scheduler)
    try:
        df = sweep(case, spec.get("parameters", spec.get("variant")), client=client,
                   fields=fields, workers=spec.get("workers"))
    finally:
        if client is not None:
            client.close()
    out = args.output or os.path.splitext(args.file)[0] + ".csv"
    df.to_csv(out)
    failed = int((df["status"] != "converged").sum())
    print(f"{len(df)} variants, {failed} not converged; table in {out}")
    return 1 if failed else 0


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m tribo")
    sub = p.add_subparsers(dest="command", required=True)
    s = sub.add_parser("sweep", help="run the variants of a case described by SWEEP.toml")
    s.add_argument("file")
    s.add_argument("--scheduler", help="a Dask scheduler's address (tcp://HOST:PORT)")
    s.add_argument("-o", "--output", help="the CSV table (default: SWEEP.csv)")
    args = p.parse_args(argv)
    try:
        return _sweep(args)
    except (TriboError, ValueError, TypeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
