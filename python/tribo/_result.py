"""`run`, `read_mesh` and what they return. The numbers come from the same library
functions as the `tribo run` command's files (results.json, history.csv, result.vtu)."""

import io
import json
import os

import numpy as np
import pandas as pd

from . import _native

# What the nodal arrays hold, in the case's units ("length", "force" and "stress" are
# whatever the case uses consistently: mm, N and MPa for SSNP154).
FIELD_UNITS = {
    "coordinates": "length",
    "displacement": "length",
    "reactions": "force (per unit thickness in plane models, total in axisymmetry)",
    "stress": "stress (Cauchy xx, yy, zz, xy)",
    "von_mises": "stress",
    "pk2": "stress (second Piola-Kirchhoff xx, yy, zz, xy; large kinematics only)",
    "contact_pressure": "stress (NaN off the slave surfaces)",
    "contact_shear": "stress (NaN off the slave surfaces)",
    "contact_gap": "length (NaN off the slave surfaces)",
    "contact_status": "code: -1 off the slave surfaces, else a key of STATUS",
}
STATUS = {0: "open", 1: "stick", 2: "slip"}
# pandas reads floats exactly from version 3 on (and deprecates the option); before, only so
EXACT_CSV = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}


def _source(case, base_dir):
    """(source, is_path, base_dir, name) for the native run."""
    if isinstance(case, dict):
        return _native.dict_to_toml(case), False, base_dir or os.getcwd(), "case dict"
    if isinstance(case, os.PathLike):
        return os.fspath(case), True, "", ""
    if isinstance(case, str):
        # TOML text has a newline or an '='; a path has neither (or names a file)
        if ("\n" in case or "=" in case) and not os.path.isfile(case):
            return case, False, base_dir or os.getcwd(), "case text"
        return case, True, "", ""
    raise TypeError(
        f"case is a TOML file path, TOML text or a dict, got {type(case).__name__}"
    )


def load_case(case):
    """A case (path or TOML text) as a dict, checked against the case format."""
    source, is_path, _, _ = _source(case, None)
    return _native.load_case(source, is_path)


def run(case, base_dir=None, threads=None):
    """Solves `case`: a TOML file path, TOML text, or a dict of the same tables. A mesh file
    named by text or a dict is relative to `base_dir` (default: the current folder).

    Raises CaseError for a case that cannot be run and SolveError for a failed solve (with
    `.report`, the Newton report, and `.time`, the time of the failing step); both are
    TriboError and carry tribo's message. The GIL is released while solving. `threads`:
    the threads of the element kernels (default: all cores)."""
    return Result(_native.run(*_source(case, base_dir), threads))


class Result:
    """A solved case.

    results      results.json's content as a dict (as `tribo run` writes it, less `case`
                 and `files`)
    probes       {name: value}
    contact      per contact pair: resultants, forces, contact length, peak, counts
    reactions    {support group: {"rx": .., "ry": ..}}
    history      pandas DataFrame: history.csv's columns, one row per output time
    report       the Newton report (dict): steps, iterations, residuals, factorisations
    coordinates, displacement, reactions_nodal (n, 2); stress, pk2 (n, 4); von_mises,
    contact_pressure, contact_shear, contact_gap (n,); contact_status (n,) int8
    """

    def __init__(self, native):
        self._native = native
        self.results = json.loads(native.results_json())
        self._fields = {}
        self._history = None

    @property
    def history(self):
        # parsed on first use: pandas' reader costs about 1.5 ms, a third of the budget
        # the call has on top of the solve
        if self._history is None:
            text = self._native.history_csv()
            self._history = (
                pd.read_csv(io.StringIO(text), **EXACT_CSV)
                if text is not None
                else pd.DataFrame()
            )
        return self._history

    probes = property(lambda self: self.results["probes"])
    contact = property(lambda self: self.results["contact"])
    reactions = property(lambda self: self.results["reactions"])
    report = property(lambda self: self.results["solver"])
    wall_s = property(lambda self: self.results["wall_s"])

    def field(self, name):
        """A nodal field by name (see FIELD_UNITS); None if the run has none (pk2 in small
        strains). The arrays are read-only views, computed once."""
        if name not in self._fields:
            got = self._native.field(name)
            if got is None:
                self._fields[name] = None
            else:
                data, cols = got
                a = np.frombuffer(data, dtype="<f8")
                a = a.reshape(-1, cols) if cols > 1 else a
                if name == "contact_status":
                    a = np.where(np.isnan(a), -1, a).astype(np.int8)
                self._fields[name] = a
        return self._fields[name]

    coordinates = property(lambda self: self.field("coordinates"))
    displacement = property(lambda self: self.field("displacement"))
    reactions_nodal = property(lambda self: self.field("reactions"))
    stress = property(lambda self: self.field("stress"))
    von_mises = property(lambda self: self.field("von_mises"))
    pk2 = property(lambda self: self.field("pk2"))
    contact_pressure = property(lambda self: self.field("contact_pressure"))
    contact_shear = property(lambda self: self.field("contact_shear"))
    contact_gap = property(lambda self: self.field("contact_gap"))
    contact_status = property(lambda self: self.field("contact_status"))

    def node_group(self, name):
        """The nodes of a mesh group (0-based indices into the nodal arrays)."""
        return np.array(self._native.node_group(name), dtype=np.int64)

    @property
    def groups(self):
        return self._native.groups()

    def write_vtu(self, path):
        """Writes the final state as `tribo run`'s result.vtu (for ParaView)."""
        self._native.write_vtu(os.fspath(path))

    def __repr__(self):
        m = self.results["mesh"]
        return (
            f"<tribo.Result {self.results['title']!r}: {m['nodes']} nodes, "
            f"{self.report['total_iterations']} Newton iterations, probes {self.probes}>"
        )


class Mesh:
    """A mesh read by tribo: coordinates (n, 2), cell_types and cells (node lists, 0-based),
    groups, node_group(name), cell_group(name)."""

    def __init__(self, native):
        self._native = native
        self.coordinates = np.frombuffer(native.coordinates(), dtype="<f8").reshape(-1, 2)
        self.cell_types = native.cell_types()
        self.cells = native.cells()
        self.groups = native.groups()

    num_nodes = property(lambda self: self._native.num_nodes())
    num_cells = property(lambda self: self._native.num_cells())

    def node_group(self, name):
        return np.array(self._native.node_group(name), dtype=np.int64)

    def cell_group(self, name):
        cells = self._native.cell_group(name)
        return None if cells is None else np.array(cells, dtype=np.int64)

    def __repr__(self):
        return f"<tribo.Mesh {self.num_nodes} nodes, {self.num_cells} cells, groups {self.groups}>"


def read_mesh(path):
    """Reads a mesh file (Gmsh .msh, MED .med/.mmed, .vtu) as `tribo mesh info` does."""
    return Mesh(_native.read_mesh(os.fspath(path)))
