"""The Python package's costs (BENCHMARKS.md, "Python package"):

1. what `tribo.run` adds to a run: the call's wall time less the time the library measures
   from reading the case to the results in memory (`wall_s`), SSNP154 A from a path and from
   a dict, median and 90th percentile of N calls;
2. a 12-variant friction sweep of SSNP154 C on a Dask LocalCluster of 2 single-threaded
   worker processes against the same variants one after another in this process, rounds
   interleaved.

    python python/bench/bench_python.py [N] [ROUNDS]
"""

import os
import pathlib
import statistics
import sys
import time

import tribo

ROOT = pathlib.Path(__file__).resolve().parents[2]
A = ROOT / "cases" / "ssnp154" / "a.toml"
C = ROOT / "cases" / "ssnp154" / "c.toml"
MUS = [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6, -0.1]


def overhead(source, n):
    extra, total = [], []
    for _ in range(n):
        t0 = time.perf_counter()
        r = tribo.run(source)
        t = time.perf_counter() - t0
        extra.append((t - r.wall_s) * 1e3)
        total.append(t * 1e3)
    q = statistics.quantiles(extra, n=10)
    return statistics.median(extra), q[-1], statistics.median(total)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 30
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    print(f"load average before: {os.getloadavg()}")
    tribo.run(A)  # warm-up
    for name, source in [("path", str(A)), ("dict", tribo.load_case(str(A)))]:
        med, p90, tot = overhead(source, n)
        print(f"run(A from {name}): adds {med:.2f} ms median, {p90:.2f} ms p90 "
              f"(call {tot:.1f} ms median, {n} calls)")
    r = tribo.run(A)
    t0 = time.perf_counter()
    _ = (r.history, r.displacement, r.stress, r.contact_pressure, r.contact_status)
    print(f"history and 4 nodal arrays on first access: {(time.perf_counter() - t0) * 1e3:.2f} ms")

    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        tribo.sweep(str(C), {"contact.0.friction": MUS[:2]}, client=client)  # warm-up
        serial, dask = [], []
        for _ in range(rounds):
            t0 = time.perf_counter()
            s = tribo.sweep(str(C), {"contact.0.friction": MUS}, workers=1)
            serial.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            d = tribo.sweep(str(C), {"contact.0.friction": MUS}, client=client)
            dask.append(time.perf_counter() - t0)
        assert (s["DY_B"].fillna(0) == d["DY_B"].fillna(0)).all()
    ratios = [b / a for a, b in zip(serial, dask)]
    print(f"12-variant sweep: serial {statistics.median(serial):.3f} s, Dask 2 workers "
          f"{statistics.median(dask):.3f} s (medians of {rounds}); ratio "
          f"{statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f})")
    print(f"sum of the variants' own wall times (serial): {s['wall_s'].sum():.3f} s")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
