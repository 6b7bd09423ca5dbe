"""tribo.sweep: a 12-variant friction sweep of SSNP154 C (Coulomb) on a Dask LocalCluster
with 2 workers equals the serial sweep and single runs, a failing variant is a row; the
overrides reach the case; field output per variant."""

import pandas as pd
import pytest

import tribo
from conftest import CASES

C = CASES / "c.toml"
# 11 frictional variants and one the case checks refuse (a negative coefficient)
MUS = [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6, -0.1]


@pytest.fixture(scope="module")
def serial():
    return tribo.sweep(str(C), {"contact.0.friction": MUS}, workers=1)


def check_rows(df):
    assert len(df) == 12
    assert list(df["contact.0.friction"]) == MUS
    ok = df[df["status"] == "converged"]
    assert len(ok) == 11
    bad = df.loc[11]
    assert bad["status"] == "error"
    assert "[[contact]] 1 (Bottom_C on Top_B): friction" in bad["error"]
    assert pd.isna(bad["DY_B"])
    assert ok["error"].isna().all()
    assert (df["wall_s"] > 0).all()


def test_serial_rows_are_single_runs(serial):
    check_rows(serial)
    case = tribo.load_case(str(C))
    for i in (0, 6):
        case["contact"][0]["friction"] = MUS[i]
        r = tribo.run(case)
        row = serial.loc[i]
        assert row["DY_B"] == r.probes["DY_B"]
        assert row["SIYY_B"] == r.probes["SIYY_B"]
        pair = r.contact[0]
        assert row["contact1_normal"] == pair["normal_resultant"]
        assert row["contact1_tangential"] == pair["tangential_resultant"]
        assert [row["contact1_fx"], row["contact1_fy"]] == pair["force"]
        assert row["ry_Encast"] == r.reactions["Encast"]["ry"]
        assert row["iterations"] == r.report["total_iterations"]
    # friction acts: the tangential resultant grows with the coefficient at first
    assert serial.loc[0, "contact1_tangential"] < serial.loc[1, "contact1_tangential"]


def test_dask_local_cluster_equals_serial(serial):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        df = tribo.sweep(str(C), {"contact.0.friction": MUS}, client=client)
    check_rows(df)
    cols = [c for c in serial.columns if c != "wall_s"]
    pd.testing.assert_frame_equal(df[cols], serial[cols], check_exact=True)


def test_local_threads_equal_serial(serial):
    df = tribo.sweep(str(C), {"contact.0.friction": MUS}, workers=2)
    cols = [c for c in serial.columns if c != "wall_s"]
    pd.testing.assert_frame_equal(df[cols], serial[cols], check_exact=True)


def test_overrides_reach_the_case_and_fields_are_written(tmp_path):
    a = CASES / "a.toml"
    df = tribo.sweep(
        str(a),
        [{"force.0.fy": -8750.0}, {"mesh.size": 3.0, "solver.steps": 1}],
        fields=tmp_path / "fields",
    )
    assert list(df["status"]) == ["converged", "converged"]
    # half the load: the support carries 8750 N
    assert df.loc[0, "ry_Encast"] == pytest.approx(8750.0, rel=1e-9)
    assert df.loc[1, "ry_Encast"] == pytest.approx(17500.0, rel=1e-9)
    # a coarser mesh: a different (converged) answer near the fine one
    fine = tribo.run(a)
    assert df.loc[1, "DY_B"] != fine.probes["DY_B"]
    assert df.loc[1, "DY_B"] == pytest.approx(fine.probes["DY_B"], rel=0.05)
    for i in (0, 1):
        folder = tmp_path / "fields" / f"variant_{i:04d}"
        assert (folder / "result.vtu").stat().st_size > 1000
        assert (folder / "history.csv").is_file()


def test_grid_and_bad_addresses():
    assert tribo._sweep.variants({"a": [1, 2], "b": [3, 4, 5]})[-1] == {"a": 2, "b": 5}
    assert len(tribo._sweep.variants({"a": [1, 2], "b": [3, 4, 5]})) == 6
    with pytest.raises(ValueError, match="'contact.3.friction': contact is an array of 1"):
        tribo.sweep(str(C), {"contact.3.friction": [0.1]})
    with pytest.raises(ValueError, match="'mesh.size.x': mesh.size is a value"):
        tribo.sweep(str(C), {"mesh.size.x": [0.1]})
    with pytest.raises(TypeError):
        tribo.sweep(str(C), 3)


def test_python_m_tribo_sweep_with_a_scheduler(tmp_path, serial):
    """`python -m tribo sweep` on a scheduler given by its address, as on a cluster."""
    distributed = pytest.importorskip("distributed")
    from tribo.__main__ import main

    spec = tmp_path / "sweep.toml"
    spec.write_text(
        f'case = "{C.as_posix()}"\n[parameters]\n"contact.0.friction" = {MUS[:3] + MUS[-1:]}\n'
    )
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        code = main(["sweep", str(spec), "--scheduler", cluster.scheduler_address])
    assert code == 1  # one variant did not converge
    df = pd.read_csv(tmp_path / "sweep.csv", index_col="variant")
    assert list(df["status"]) == ["converged"] * 3 + ["error"]
    assert list(df["DY_B"][:3]) == list(serial["DY_B"][:3])
    (tmp_path / "bad.toml").write_text('case = "x.toml"\nparameter = 1\n')
    assert main(["sweep", str(tmp_path / "bad.toml")]) == 2
