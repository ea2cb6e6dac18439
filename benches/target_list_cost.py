"""The cost of a target list's handling in ``v2ref.plan_targets`` with
``progress=`` (rows planned one call at a time) and with ``client=`` (a
Dask task per row), the plans themselves made free: every row has a
magnitude out of range, so it is marked bad at once and only the list's
parsing and shipping are timed.

    python benches/target_list_cost.py progress 4000
    python benches/target_list_cost.py client 2000

Prints rows, seconds and the calling process's peak resident memory
(ru_maxrss), and what a task is sent (pickled bytes of its arguments).
"""

import pickle
import resource
import sys
import time

import v2ref
from v2ref import dask as v2dask


def rows(n):
    return [{"name": f"star {i}", "magnitude": 99.0, "band": "H"} for i in range(n)]


def main():
    mode, n = sys.argv[1], int(sys.argv[2])
    sent = []
    task = v2dask._target_rows

    def measured(*args):
        sent.append(len(pickle.dumps(args)))
        return task(*args)

    client = cluster = None
    if mode == "client":
        from distributed import Client, LocalCluster

        cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
        submit = client.submit

        def submit_measured(f, *args, **kw):
            sent.append(len(pickle.dumps(args)))
            return submit(f, *args, **kw)

        client.submit = submit_measured
    else:
        v2dask._target_rows = measured
    t0 = time.perf_counter()
    if mode == "client":
        table = v2ref.plan_targets(rows(n), throughput=0.01, client=client)
    else:
        table = v2ref.plan_targets(rows(n), throughput=0.01, progress=lambda d, t: None)
    seconds = time.perf_counter() - t0
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"{mode}: {n} rows in, {len(table)} out, {seconds:.2f} s, peak RSS {peak_mb:.0f} MB, "
          f"a task sent {min(sent)}-{max(sent)} bytes ({sum(sent) / 1e6:.1f} MB in all)")
    if client is not None:
        client.close()
        cluster.close()


if __name__ == "__main__":
    main()
