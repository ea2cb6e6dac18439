#!/usr/bin/env python3
"""The vectorised NumPy Monte Carlo a user would write instead of
`v2ref simulate`: batches of 128-sample noisy interferograms, one FFT per
interferogram (numpy.fft along the batch axis), both estimators, running
means and variances. Prints interferograms per second for Gaussian detector
noise and Poisson photon noise, all bins and the positive-frequency window.

Run beside `cargo bench --bench montecarlo` on the same machine:
    python3 benches/numpy_baseline.py [--trials 1000000] [--batch 65536]

The noise-free interferogram is the Appendix case (flat 2.0-2.4 um band in
wavenumber, centred scan, 0.5 um sampling, c = n = 10, m_0 = n), computed
here in closed form: m(x) = n sinc(dsigma x) cos(2 pi sigma_c x).
"""
import argparse
import time

import numpy as np


def interferogram(n_samples=128, dx=0.5, photons=10.0):
    lo, hi = 1 / 2.4, 1 / 2.0
    i = np.arange(n_samples)
    x = np.where(i < (n_samples + 1) // 2, i, i - n_samples) * dx
    m = photons * np.sinc((hi - lo) * x) * np.cos(np.pi * (lo + hi) * x)
    return m, np.full(n_samples, photons)


def run(kind, window, trials, batch, seed=1):
    m, c = interferogram()
    n = m.size
    bins = np.arange(n) if window == "all" else np.arange(1, n // 2)
    rng = np.random.default_rng(seed)
    s1 = s1sq = s2 = s2sq = 0.0
    done = 0
    t0 = time.perf_counter()
    while done < trials:
        b = min(batch, trials - done)
        if kind == "gaussian":
            samples = m + 2.0 * rng.standard_normal((b, n))
        else:
            samples = rng.poisson(m + c, size=(b, n)) - c
        spec = np.fft.fft(samples, axis=1)[:, bins]
        v1 = np.sum(spec.real ** 2 + spec.imag ** 2, axis=1)
        tot = spec.sum(axis=1)
        v2 = tot.real ** 2 + tot.imag ** 2
        s1 += v1.sum(); s1sq += (v1 ** 2).sum()
        s2 += v2.sum(); s2sq += (v2 ** 2).sum()
        done += b
    dt = time.perf_counter() - t0
    return trials / dt, s1 / trials, s2 / trials


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=1_000_000)
    ap.add_argument("--batch", type=int, default=65536)
    a = ap.parse_args()
    print(f"numpy {np.__version__}, {a.trials} interferograms of 128 samples, batch {a.batch}")
    for kind in ("gaussian", "poisson"):
        for window in ("all", "positive"):
            rate, mean1, mean2 = run(kind, window, a.trials, a.batch)
            print(f"{kind:9s} {window:9s} {rate:12.4g} interferograms/s   (mean V1^2 {mean1:.4e}, V2^2 {mean2:.4e})")


if __name__ == "__main__":
    main()
