"""Benchmark of ``v2ref.dask``: the cost of a work unit against a Dask
task's round trip, the range size that keeps the overhead under 5 %, and
the speed-up of ``simulate`` from 1 to 2 worker processes.

    .venv/bin/python benches/dask_units.py [--units 24] [--samples 128]

Needs the package built in release (``pip install .``) and dask.distributed.
Prints the load average: on a shared machine the timings are upper bounds.
"""

import argparse
import os
import time

import distributed

import v2ref
from v2ref import dask as v2dask


def simulate_args(samples, trials, **kw):
    """The arguments ``v2ref.simulate`` hands ``v2ref.dask`` (threads 1)."""
    seen = {}

    def capture(command, args, client, checkpoint, chunk_units):
        seen["args"] = args
        return (None, 0)

    real = v2dask._run_units
    v2dask._run_units = capture
    try:
        v2ref.simulate(trials=trials, samples=samples, threads=1, checkpoint="-", **kw)
    finally:
        v2dask._run_units = real
    return seen["args"]


def best_of(repeats, f):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def noop(x):
    return x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--units", type=int, default=512, help="work units of the speed-up run")
    ap.add_argument("--samples", type=int, default=128)
    opts = ap.parse_args()
    print(f"load average before: {os.getloadavg()}, cores: {os.cpu_count()}")

    args = simulate_args(opts.samples, 4 * 8192)
    unit_s = best_of(3, lambda: v2ref._v2ref._units_run("simulate", args, 0, 4)) / 4
    print(f"one unit (8192 rows, {opts.samples} samples, 1 thread): {unit_s * 1e3:.1f} ms")
    rows_args = simulate_args(opts.samples, 2 * 8192, bias="counts")
    rows_s = best_of(2, lambda: v2ref._v2ref._units_run("simulate", rows_args, 0, 2)) / 2
    print(f"one unit with every row estimated (bias counts): {rows_s * 1e3:.1f} ms "
          f"({rows_s / 8192 * 1e6:.2f} us a row)")

    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        client.submit(noop, 0, pure=False).result()
        n = 200
        trip = best_of(3, lambda: [client.submit(noop, i, pure=False).result() for i in range(n)]) / n
        many = best_of(3, lambda: client.gather(client.map(noop, range(n), pure=False))) / n
        print(f"task round trip, one at a time: {trip * 1e3:.2f} ms; per task of {n} mapped: {many * 1e3:.2f} ms")
        overhead_s = trip
        # A range's own work besides its units: the model built again,
        # the partial encoded and sent back.
        per_range = best_of(3, lambda: v2ref._v2ref._units_run("simulate", args, 0, 1)) - unit_s
        overhead_s += max(per_range, 0.0)
        chunk = max(1, -(-overhead_s // (0.05 * unit_s)))
        print(f"overhead per range (round trip + setup): {overhead_s * 1e3:.1f} ms "
              f"-> ranges of >= {int(chunk)} unit(s) keep it under 5 % "
              f"(v2ref.dask.MIN_UNITS_PER_TASK = {v2dask.MIN_UNITS_PER_TASK}: "
              f"{100 * overhead_s / (v2dask.MIN_UNITS_PER_TASK * unit_s):.1f} %)")

    trials = opts.units * 8192
    run_args = simulate_args(opts.samples, trials)
    one_process = best_of(2, lambda: v2ref.simulate(trials=trials, samples=opts.samples, threads=1))
    print(f"{opts.units} units in one process, 1 thread: {one_process:.2f} s")
    timings = {}
    for workers in (1, 2):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address=None) as cluster, distributed.Client(cluster) as client:
            client.submit(noop, 0, pure=False).result()
            chunk = v2dask.MIN_UNITS_PER_TASK
            # The run releases its keys when done: a repeat computes again.
            timings[workers] = best_of(
                2, lambda: v2dask._run_units("simulate", run_args, client, None, chunk))
    print(f"on 1 worker: {timings[1]:.2f} s; on 2 workers: {timings[2]:.2f} s; "
          f"speed-up {timings[1] / timings[2]:.2f} (2 cores shared)")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
