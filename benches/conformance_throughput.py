#!/usr/bin/env python3
"""Throughput of the conformance kit, release build (standard library only).

On 10^6 interferograms of 128 samples with photon noise (10 photons per
sample), the size the kit's performance targets are stated for:

- ``synth`` <= 2 x (``simulate`` of the same draws + writing the same bytes
  with fsync);
- ``estimate`` < 2 s (reading the 1 GB .npy, both estimators, writing the
  answers);
- ``plan`` over its default grid (2 estimators x 20 fringe frequencies x 4
  strokes, 1000 piston scans each) < 10 s, on the README's H-band question.

Prints the best of ``REPEAT`` runs (default 3) of each and the ratios to the
limits. Run from anywhere: ``python3 benches/conformance_throughput.py``.
"""

import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "target", "release", "v2ref")
ROWS, SAMPLES = 1_000_000, 128
REPEAT = int(os.environ.get("REPEAT", "3"))


def best(fn):
    times = []
    for _ in range(REPEAT):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def run(*args):
    subprocess.run([BIN, *args], check=True, stdout=subprocess.DEVNULL)


def write_bytes(path, nbytes):
    block = bytes(1 << 20)
    with open(path, "wb") as f:
        for _ in range(nbytes // len(block)):
            f.write(block)
        f.write(bytes(nbytes % len(block)))
        f.flush()
        os.fsync(f.fileno())
    os.remove(path)


def main():
    subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    with tempfile.TemporaryDirectory() as d:
        stem = os.path.join(d, "big")
        nbytes = ROWS * SAMPLES * 8
        sim = best(lambda: run("simulate", "--trials", str(ROWS), "--samples", str(SAMPLES), "--quiet"))
        write = best(lambda: write_bytes(os.path.join(d, "zero.bin"), nbytes))
        synth = best(lambda: run("synth", "--out", stem, "--rows", str(ROWS), "--samples", str(SAMPLES),
                                 "--reference-blocks", "0", "--quiet"))
        est = best(lambda: run("estimate", "--sidecar", stem + ".json", "--out", os.path.join(d, "est.npy")))
    plan = best(lambda: run("plan", "--wavelength-um", "1.65", "--bandwidth-nm", "300", "--source", "ud",
                            "--diameter-mas", "2", "--baseline-m", "100", "--photon-rate-per-s", "1e6",
                            "--target-sigma-v2", "1e-3", "--quiet"))
    limit = 2 * (sim + write)
    print(f"machine: {os.cpu_count()} cores; best of {REPEAT}")
    print(f"simulate, {ROWS} rows x {SAMPLES}       {sim:6.2f} s")
    print(f"write {nbytes / 2**20:.0f} MiB with fsync         {write:6.2f} s")
    print(f"synth to .npy                    {synth:6.2f} s  limit {limit:.2f} s, ratio {synth / limit:.2f}")
    print(f"estimate the .npy                {est:6.2f} s  limit 2.00 s, ratio {est / 2:.2f}")
    print(f"plan, default grid               {plan:6.2f} s  limit 10.00 s, ratio {plan / 10:.2f}")
    return 0 if synth <= limit and est < 2 and plan < 10 else 1


if __name__ == "__main__":
    sys.exit(main())
