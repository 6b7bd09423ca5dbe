"""Checks tribo's mesh and result files with an independent reader (meshio, which reads
MED through h5py): run by .ci/check_formats.sh.

usage: check_formats.py mesh SOURCE.mmed OURS.vtu OURS.med REFERENCE.msh
       check_formats.py result RUN_DIR
"""
import csv
import json
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np

errors = []


def fail(msg):
    errors.append(msg)
    print("  FAIL:", msg)


def two_d(kind):
    return kind in ("triangle", "triangle6", "quad", "quad8")


def cell_sets(mesh, dims=("2d",)):
    """{kind: set of sorted node tuples} of the 2D and 1D cells."""
    out = {}
    for block in mesh.cells:
        if block.type == "vertex":
            continue
        out.setdefault(block.type, set()).update(tuple(sorted(c)) for c in block.data)
    return out


def signed_areas(mesh):
    """Signed areas of the 2D cells (corner polygon)."""
    areas = []
    p = mesh.points
    for block in mesh.cells:
        if not two_d(block.type):
            continue
        k = 3 if block.type.startswith("triangle") else 4
        c = block.data[:, :k]
        x, y = p[c, 0], p[c, 1]
        areas.append(0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1))
    return np.concatenate(areas)


def med_groups(mesh):
    """MED families as read by meshio -> {group: (set of node ids, set of cell tuples)}."""
    groups = {}
    for tag, names in mesh.point_tags.items():
        nodes = set(np.nonzero(mesh.point_data["point_tags"] == tag)[0].tolist())
        for n in names:
            groups.setdefault(n, [set(), set()])[0].update(nodes)
    for tag, names in mesh.cell_tags.items():
        for block, tags in zip(mesh.cells, mesh.cell_data["cell_tags"]):
            cells = block.data[tags == tag]
            for n in names:
                g = groups.setdefault(n, [set(), set()])
                g[0].update(cells.ravel().tolist())
                if block.type != "vertex":
                    g[1].update(tuple(sorted(c)) for c in cells)
    return groups


def vtu_groups(mesh):
    """Our VTU mesh file: group_NAME cell flags and nodes_NAME point flags."""
    groups = {}
    for name, arrays in mesh.cell_data.items():
        if not name.startswith("group_"):
            continue
        g = groups.setdefault(name[6:], [set(), set()])
        for block, flags in zip(mesh.cells, arrays):
            cells = block.data[np.asarray(flags).ravel() == 1]
            g[0].update(cells.ravel().tolist())
            if block.type != "vertex":
                g[1].update(tuple(sorted(c)) for c in cells)
    for name, flags in mesh.point_data.items():
        if name.startswith("nodes_"):
            g = groups.setdefault(name[6:], [set(), set()])
            g[0].update(np.nonzero(np.asarray(flags).ravel() == 1)[0].tolist())
    return groups


def same_groups(label, a, b, compare_cells=True):
    if set(a) != set(b):
        fail(f"{label}: groups {sorted(a)} != {sorted(b)}")
        return
    for name in a:
        if a[name][0] != b[name][0]:
            fail(f"{label}: group {name}: node sets differ ({len(a[name][0])} / {len(b[name][0])})")
        if compare_cells and a[name][1] and b[name][1] and a[name][1] != b[name][1]:
            fail(f"{label}: group {name}: cell sets differ")


def check_mesh(source_med, ours_vtu, ours_med, reference_msh):
    src = meshio.read(source_med, file_format="med")
    vtu = meshio.read(ours_vtu)
    print(f"  {source_med}: {len(src.points)} nodes, cells {[(b.type, len(b.data)) for b in src.cells]}")
    # Same nodes (1e-12), same 2D and grouped 1D cells as node sets, groups.
    if src.points.shape[0] != vtu.points.shape[0] or np.max(np.abs(src.points[:, :2] - vtu.points[:, :2])) > 1e-12:
        fail(f"{ours_vtu}: nodes differ from {source_med}")
    s_cells, v_cells = cell_sets(src), cell_sets(vtu)
    for kind in v_cells:
        if two_d(kind) and s_cells.get(kind) != v_cells[kind]:
            fail(f"{ours_vtu}: {kind} cells differ from {source_med}")
    # Orientation: MED stores 2D cells clockwise, tribo counter-clockwise.
    if not np.all(signed_areas(src) < 0):
        fail(f"{source_med}: expected clockwise cells as read by meshio")
    if not np.all(signed_areas(vtu) > 0):
        fail(f"{ours_vtu}: cells are not all counter-clockwise")
    same_groups(f"{ours_vtu} vs {source_med}", med_groups(src), vtu_groups(vtu))
    # Our MED file (written from the .msh) read by meshio's MED reader, against the source
    # MED file (meshio's MSH reader keeps one physical group per element, MED families
    # keep them all). Ungrouped 1D cells are in the source MED only (Gmsh drops them).
    med = meshio.read(ours_med, file_format="med")
    msh = meshio.read(reference_msh)
    if np.max(np.abs(med.points[:, :2] - src.points[:, :2])) > 1e-12 or len(msh.points) != len(med.points):
        fail(f"{ours_med}: nodes differ from {source_med}")
    m_cells = cell_sets(med)
    for kind in s_cells:
        if two_d(kind) and m_cells.get(kind) != s_cells[kind]:
            fail(f"{ours_med}: {kind} cells differ from {source_med}")
    if not np.all(signed_areas(med) < 0):
        fail(f"{ours_med}: 2D cells must be stored clockwise (MED convention)")
    gm = med_groups(med)
    same_groups(f"{ours_med} vs {source_med}", gm, med_groups(src))
    print(f"  {ours_vtu} and {ours_med}: nodes, cells, orientation and {len(gm)} groups checked")


def check_result(run_dir):
    res = meshio.read(f"{run_dir}/result.vtu")
    pd = res.point_data
    for field in ["displacement", "stress", "von_mises", "reaction", "contact_pressure",
                  "contact_shear", "contact_gap", "contact_status", "contact_multiplier_normal",
                  "contact_multiplier_tangential"]:
        if field not in pd:
            fail(f"result.vtu: no point field {field}")
    for field in ["material", "group_Block", "group_Cylinder"]:
        if field not in res.cell_data:
            fail(f"result.vtu: no cell field {field}")
    rows = list(csv.DictReader(open(f"{run_dir}/pressure.csv")))
    worst = 0.0
    for r in rows:
        n = int(r["node"]) - 1
        x = res.points[n, :2]
        if abs(x[0] - float(r["x"])) > 1e-12 or abs(x[1] - float(r["y"])) > 1e-12:
            fail(f"node {n + 1}: VTU point {x} != CSV ({r['x']}, {r['y']})")
        xd = x + pd["displacement"][n, :2]
        worst = max(worst, abs(xd[0] - float(r["x_deformed"])), abs(xd[1] - float(r["y_deformed"])))
        p = float(r["pressure"])
        if abs(pd["contact_pressure"][n] - p) > 1e-9 * max(1.0, abs(p)):
            fail(f"node {n + 1}: VTU contact_pressure {pd['contact_pressure'][n]} != CSV {p}")
        if r["shear"] and abs(pd["contact_shear"][n] - float(r["shear"])) > 1e-9 * max(1.0, abs(p)):
            fail(f"node {n + 1}: VTU contact_shear != CSV")
        # point-to-segment (case C): the normal multiplier is -p
        if abs(pd["contact_multiplier_normal"][n] + p) > 1e-9 * max(1.0, abs(p)):
            fail(f"node {n + 1}: contact_multiplier_normal != -pressure")
    if worst > 1e-9:
        fail(f"deformed coordinates differ from the CSV by {worst}")
    status = pd["contact_status"]
    closed = [int(r["node"]) - 1 for r in rows if float(r["pressure"]) > 1e-6]
    if not closed or not all(status[n] in (1.0, 2.0) for n in closed):
        fail("loaded slave nodes must have status stick (1) or slip (2)")
    # The curve along the block top: arc length increasing, values those of the VTU.
    curve = list(csv.DictReader(open(f"{run_dir}/curve_Top_B.csv")))
    s_prev = -1.0
    for r in curve:
        n = int(r["node"]) - 1
        if float(r["s"]) <= s_prev:
            fail("curve_Top_B.csv: arc length not increasing")
        s_prev = float(r["s"])
        if abs(pd["displacement"][n, 1] - float(r["dy"])) > 1e-12 or abs(pd["stress"][n, 1] - float(r["siyy"])) > 1e-9 * max(1.0, abs(float(r["siyy"]))):
            fail(f"curve_Top_B.csv: node {n + 1} differs from result.vtu")
    # The time series: every step readable, times increasing, the last one = result.vtu.
    pvd = ET.parse(f"{run_dir}/steps/step.pvd").getroot()
    sets = pvd.findall("./Collection/DataSet")
    times = [float(s.get("timestep")) for s in sets]
    if not sets or times != sorted(times) or abs(times[-1] - 1.0) > 1e-12:
        fail(f"step.pvd: times {times}")
    last = None
    for s in sets:
        last = meshio.read(f"{run_dir}/steps/{s.get('file')}")
    if last is not None and np.max(np.abs(last.point_data["displacement"] - pd["displacement"])) > 0:
        fail("last step of step.pvd differs from result.vtu")
    print(f"  {run_dir}: {len(rows)} slave nodes checked against pressure.csv, {len(curve)} curve nodes, "
          f"{len(sets)} steps in step.pvd (times {times})")


if __name__ == "__main__":
    if sys.argv[1] == "mesh":
        check_mesh(*sys.argv[2:6])
    else:
        check_result(sys.argv[2])
    if errors:
        sys.exit(1)
