#!/usr/bin/env python3
"""Check your own V² estimator against v2ref's truth, all in Python.

1. ``v2ref.synthesize`` draws a set of noisy interferograms whose truth
   (what an unbiased estimator must give, with standard errors) is in the
   sidecar;
2. ``my_pipeline`` stands for your code: plain NumPy, it knows nothing of
   v2ref beyond the sidecar's continuum and calibration;
3. ``v2ref.score`` says whether its per-row V1² and V2² reach the truth.

Run::

    python examples/python/validate_my_pipeline.py            # PASS
    python examples/python/validate_my_pipeline.py --forget-bias   # FAIL

Needs the package: ``pip install .`` at the top of the repository.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

import v2ref


def my_pipeline(rows: np.ndarray, continuum: np.ndarray, read_noise: float,
                calibration: tuple, subtract_bias: bool = True) -> dict:
    """A user's estimator: V1² = Σ|B_k|², V2² = |Σ B_k|² over the positive
    bins, minus the photon + detector noise bias taken from each row's own
    counts, divided by the calibrator's (noise-free) estimates.

    rows: (scans, N) modulated samples M_i = I_i − c_i, photons;
    continuum: c_i, photons; read_noise: σ_det, photons per sample.
    """
    n = rows.shape[1]
    bins = np.arange(1, (n + 1) // 2)  # positive frequencies, no DC, no Nyquist
    f = np.fft.fft(rows, axis=1)[:, bins]
    v1_raw = (np.abs(f) ** 2).sum(axis=1)
    v2_raw = np.abs(f.sum(axis=1)) ** 2
    if subtract_bias:
        # Per-sample noise variance: σ_det² + the counts c_i + M_i (Poisson).
        var = read_noise**2 + continuum + rows
        kernel = np.abs(np.exp(-2j * np.pi * np.outer(np.arange(n), bins) / n).sum(axis=1)) ** 2
        v1_raw = v1_raw - len(bins) * var.sum(axis=1)
        v2_raw = v2_raw - var @ kernel
    return {"v1_sq": v1_raw / calibration[0], "v2_sq": v2_raw / calibration[1]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=20000, help="scans in the test set")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--forget-bias", action="store_true", help="a broken pipeline, to see it fail")
    args = ap.parse_args()

    config = dict(samples=128, dx_um=0.5, photons=20.0, read_noise=1.0,
                  source="ud", diameter_mas=10.0, visibility=0.9)
    rows, sidecar = v2ref.synthesize(rows=args.rows, seed=args.seed, reference_blocks=8, **config)
    print(f"synthesized {rows.shape[0]} scans of {rows.shape[1]} samples (seed {args.seed})")

    window = next(w for w in sidecar["truth"]["windows"] if w["bins"] == "positive")
    calibration = (window["calibration"]["v1_sq"], window["calibration"]["v2_sq"])
    mine = my_pipeline(rows, np.asarray(sidecar["continuum_photons"]), config["read_noise"],
                       calibration, subtract_bias=not args.forget_bias)

    # The reference implementation on the same rows, for comparison.
    ref = v2ref.estimate(rows, sidecar=sidecar, bins="positive", bias="counts")
    print(f"max |mine - v2ref| V1²: {np.abs(mine['v1_sq'] - ref['v1_sq']).max():.3e}, "
          f"V2²: {np.abs(mine['v2_sq'] - ref['v2_sq']).max():.3e}")

    report = v2ref.score(mine, sidecar, bins="positive", bias="counts")
    print(f"threshold |z| <= {report['z_crit']:.3f} (alpha {report['alpha']}, {report['tests']} tests)")
    for s in report["estimators"]:
        print(f"{s['estimator']:6}  mean {s['mean']:.6f} (truth {s['expected_mean']:.6f}, z {s['z_mean']:+.2f})"
              f"  var {s['var']:.4e} (truth {s['expected_var']:.4e}, z {s['z_var']:+.2f})"
              f"  {'PASS' if s['pass'] else 'FAIL'}")
    print("PASS" if report["pass"] else "FAIL")
    return 0 if report["pass"] else 1


if __name__ == "__main__":
    sys.exit(main())
