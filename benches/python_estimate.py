#!/usr/bin/env python3
"""`estimate` from Python and from the CLI against its floor, same rows.

The floor (`examples/estimate_timing.rs`, code in benches/floors/estimate_floor.rs)
does only the unavoidable work: a real-input FFT of each row (realfft) and
the two sums over the positive bins, on rows in memory; for the CLI, also
the .npy read and six values per row written as a .npy. On a C-contiguous
float64 array of `--rows` x `--samples` (default 200 000 x 64), for each
thread count, best of `--repeats`, the sides interleaved:

- library: `RowEstimator::estimate_rows` / floor (both in the example);
- Python: `v2ref.estimate(x)` / the in-memory floor;
- CLI: `v2ref estimate --input rows.npy --out est.npy` / the file floor
  (both whole processes, timed from here).

    pip install .   # the package
    python benches/python_estimate.py [--rows 200000] [--samples 64] [--threads 1,2]

Set CARGO_TARGET_DIR as for your build; the example and the CLI are built
with `cargo build --release --example estimate_timing --bin v2ref`.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import v2ref

ROOT = Path(__file__).resolve().parents[1]


def best_of(repeats, run):
    best = float("inf")
    for _ in range(repeats):
        t = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--rows", type=int, default=200_000)
    ap.add_argument("--samples", type=int, default=64)
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()

    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    subprocess.run(["cargo", "build", "--release", "--quiet", "--example", "estimate_timing",
                    "--bin", "v2ref"], cwd=ROOT, check=True)
    example = target / "release" / "examples" / "estimate_timing"
    cli = target / "release" / "v2ref"

    # Photon-noise-like rows around a positive level (no dark row).
    x = np.random.default_rng(1).normal(loc=10.0, scale=5.0, size=(args.rows, args.samples))
    print(f"array: {x.shape} float64, {x.nbytes / 2**20:.0f} MiB, C-contiguous {x.flags.c_contiguous}")
    print(f"{'side':<28} {'thr':>3} {'floor ms':>10} {'v2ref ms':>10} {'ratio':>6}")
    status = 0
    with tempfile.TemporaryDirectory() as d:
        raw, npy, out = Path(d) / "rows.f64", Path(d) / "rows.npy", Path(d) / "est.npy"
        x.tofile(raw)
        np.save(npy, x)
        for threads in [int(t) for t in args.threads.split(",")]:
            v2ref.estimate(x[:1000], threads=threads)  # warm up
            floor, lib_best, py = float("inf"), float("inf"), float("inf")
            for _ in range(args.repeats):
                line = subprocess.run([str(example), "memory", str(raw), str(args.samples), str(threads), "1"],
                                      check=True, capture_output=True, text=True).stdout.split()
                floor, lib_best, checksum = min(floor, float(line[2])), min(lib_best, float(line[3])), line[4]
                t = time.perf_counter()
                est = v2ref.estimate(x, threads=threads)
                py = min(py, time.perf_counter() - t)
            py_sum = float((est["v1_sq"] + est["v2_sq"]).sum())
            if abs(float(checksum) - py_sum) > 1e-9 * abs(py_sum):
                print(f"checksums differ: python {py_sum!r}, library {checksum}")
                status = 1
            print(f"{'library estimate_rows':<28} {threads:>3} {floor * 1e3:>10.2f} {lib_best * 1e3:>10.2f} {lib_best / floor:>6.2f}")
            print(f"{'python v2ref.estimate':<28} {threads:>3} {floor * 1e3:>10.2f} {py * 1e3:>10.2f} {py / floor:>6.2f}")
            file_floor, ours = float("inf"), float("inf")
            for _ in range(args.repeats):
                file_floor = min(file_floor, best_of(1, lambda: subprocess.run(
                    [str(example), "file", str(npy), str(out), str(threads)], check=True, capture_output=True)))
                ours = min(ours, best_of(1, lambda: subprocess.run(
                    [str(cli), "estimate", "--input", str(npy), "--out", str(out), "--force",
                     "--threads", str(threads)], check=True, capture_output=True)))
            print(f"{'CLI .npy -> .npy':<28} {threads:>3} {file_floor * 1e3:>10.2f} {ours * 1e3:>10.2f} {ours / file_floor:>6.2f}")
    return status


if __name__ == "__main__":
    sys.exit(main())
