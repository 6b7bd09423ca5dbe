"""tribo from Python: run a case, read its results as numpy arrays and pandas tables, run
parameter sweeps locally or on a Dask cluster.

    import tribo
    r = tribo.run("cases/ssnp154/a.toml")     # a path, TOML text or a dict
    r.probes["DY_B"], r.history, r.displacement
    df = tribo.sweep(case, {"contact.0.friction": [0.0, 0.1, 0.2]})

Units are the case's own (SSNP154: mm, N, MPa), as in the `tribo` command's files.
"""

from ._native import CaseError, SolveError, TriboError
from ._result import FIELD_UNITS, STATUS, Mesh, Result, read_mesh, run
from ._sweep import sweep

__all__ = [
    "run",
    "read_mesh",
    "sweep",
    "load_case",
    "Result",
    "Mesh",
    "TriboError",
    "CaseError",
    "SolveError",
    "FIELD_UNITS",
    "STATUS",
]

from ._result import load_case  # noqa: E402
