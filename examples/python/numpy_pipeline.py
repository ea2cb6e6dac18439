#!/usr/bin/env python3
"""A minimal NumPy pipeline for the squared-visibility estimators V1² and V2².

This is an *independent* implementation of the estimators of Perrin &
Ridgway, written from the formulas of docs/conventions.md §§5–8 with the
Python standard library and NumPy only. It does not import, call or
translate v2ref's code; it exists so that `v2ref score` can be checked
against a pipeline that v2ref did not write, and as an example for anyone
scoring their own pipeline on a `v2ref synth` set.

Input: a synth set, i.e. a JSON sidecar (format "v2ref-synth-1") and, next
to it, the float64 ``.npy`` it names in ``data.npy`` (shape (rows, N), one
scan per row, stored in DFT order: column 0 at zero OPD).

For each row, with M_i the modulated samples (the row itself when the
sidecar says ``continuum_subtracted``, else the counts I_i minus the
continuum c_i = ``continuum_photons[i]``):

    B_k      = Σ_i M_i exp(−2πi ik/N)          (numpy.fft.fft, unnormalized)
    V1²_raw  = Σ_{k∈K} |B_k|²
    V2²_raw  = |Σ_{k∈K} B_k|²

over the window K of bins (``--bins``):

    positive   k = 1 … ⌈N/2⌉ − 1
    all        k = 0 … N − 1
    band       the positive bins with σ_min ≤ k/(N δx) ≤ σ_max (edges kept)

The additive-noise bias is subtracted with v_i the noise variance of sample i:

    b1 = |K| Σ_i v_i
    b2 = Σ_i |u_i|² v_i,    u_i = Σ_{k∈K} exp(−2πi ik/N)

    v_i = σ_det² + n_i   with photon noise,   σ_det² without

where n_i is the sample's mean count, taken (``--bias``) from the model
(``model``: n_i = c + m_i) or from the row itself (``counts``:
n_i = c + M_i). The normalized estimates are (raw − bias) / C, C being the
calibrator's noise-free raw V1² and V2² over the window.

The model — the continuum c, the mean modulated counts m_i, the band's
bins and the calibration C — is computed here from the physical inputs the
sidecar states (``--model inputs``, the default), as a user's pipeline
would compute it from its instrument: a flat band [σ_min, σ_max] =
[1/(λ0 + Δλ/2), 1/(λ0 − Δλ/2)] with W = 1/(σ_max − σ_min), the source's
visibility V(σ) (point: 1; uniform disk: 2 J1(z)/z, z = π θ B σ, J1 by
its integral representation), the quadratic dispersion phase
φ = ½ D (σ − σ0)², D = 8P/Δσ², the integrating detector's sinc(σ δx),
sample positions in DFT order, and

    m_i = c V_in Re ∫ W V e^{iφ} s e^{2πiσx_i} dσ     (Gauss–Legendre),

c = ``photons``, V_in = ``visibility``; the calibrator is the same with a
point source, V_in = 1 and no phase. Piston only moves the data, not the
model. ``--model sidecar`` reads these from the sidecar instead (what
v2ref computed): then an error in v2ref's fringe model would cancel
between the data and the calibration, and this pipeline could not see it.

``--mistake`` deliberately gets one thing wrong, to check that a scorer
catches it:

    photon-bias-from-m   v_i = σ_det² + m_i (the model's modulated part,
                         m_i = mean_counts − continuum) instead of n_i
    no-calibration       no division by C

Output: CSV with header ``row,v1_sq,v2_sq``, one line per row (0-based row
index), floats written with repr() so they round-trip exactly.

Usage:
    python numpy_pipeline.py SET.json --out EST.csv [--bins positive|band|all]
                             [--bias model|counts] [--model inputs|sidecar]
                             [--mistake ...]
"""

import argparse
import csv
import json
import os
import sys

import numpy as np

FORMAT = "v2ref-synth-1"
WINDOWS = ("positive", "band", "all")
BIAS_CONVENTIONS = ("model", "counts")
MISTAKES = ("none", "photon-bias-from-m", "no-calibration")
MODELS = ("inputs", "sidecar")

# Quadrature nodes over the band: the integrand turns through a few cycles
# at most over a flat band (σ x ≤ a few tens), so 256 Gauss–Legendre
# nodes reach rounding.
BAND_NODES = 256
# Trapezoid nodes of the J1 integral over one period: exponentially
# accurate for the |z| ≲ 30 of a resolved disk on one baseline.
J1_NODES = 128
MAS_TO_RAD = np.pi / (180.0 * 3600.0 * 1000.0)


def load_set(sidecar_path):
    """The sidecar (a dict) and the rows (float64 array, shape (rows, N))."""
    with open(sidecar_path, encoding="utf-8") as f:
        sidecar = json.load(f)
    if sidecar.get("format") != FORMAT:
        raise ValueError(
            f"{sidecar_path}: format {sidecar.get('format')!r}, expected {FORMAT!r}"
        )
    folder = os.path.dirname(os.path.abspath(sidecar_path))
    rows = np.load(os.path.join(folder, sidecar["data"]["npy"]))
    rows = np.asarray(rows, dtype=np.float64)
    if rows.ndim == 1:
        rows = rows.reshape(1, -1)
    expected = (sidecar["data"]["rows"], sidecar["data"]["samples"])
    if rows.shape != tuple(expected):
        raise ValueError(f"data shape {rows.shape}, sidecar says {tuple(expected)}")
    return sidecar, rows


def window_entry(sidecar, window):
    """The sidecar's truth for one window of bins."""
    for w in sidecar["truth"]["windows"]:
        if w["bins"] == window:
            return w
    raise ValueError(f"the sidecar has no truth for window {window!r}")


def band_edges(inputs):
    """[σ_min, σ_max] (1/µm) of the stated band: only flat bands are modelled."""
    spectrum = inputs["spectrum"]
    if spectrum.get("kind") != "flat":
        raise ValueError(
            f"spectrum {spectrum.get('kind')!r}: this pipeline models flat bands only "
            "(use --model sidecar)"
        )
    lam = float(spectrum["wavelength_um"])
    half = float(spectrum["bandwidth_nm"]) / 1000.0 / 2.0
    return 1.0 / (lam + half), 1.0 / (lam - half)


def bessel_j1(z):
    """J1(z) = (1/2π) ∫_0^{2π} cos(τ − z sin τ) dτ, trapezoid over one period."""
    tau = 2.0 * np.pi * np.arange(J1_NODES) / J1_NODES
    z = np.asarray(z, dtype=np.float64)
    return np.cos(tau - z[..., None] * np.sin(tau)).mean(axis=-1)


def source_visibility(inputs, sigma):
    """The source's complex visibility at B σ (σ in 1/µm)."""
    source = inputs["source"]
    if source["kind"] == "point":
        return np.ones_like(sigma)
    if source["kind"] == "ud":
        theta_rad = float(source["diameter_mas"]) * MAS_TO_RAD
        z = np.pi * theta_rad * float(inputs["baseline_m"]) * sigma * 1e6
        small = np.abs(z) < 1e-8
        return np.where(small, 1.0, 2.0 * bessel_j1(z) / np.where(small, 1.0, z))
    raise ValueError(
        f"source {source['kind']!r}: this pipeline models point sources and uniform disks "
        "only (use --model sidecar)"
    )


def sample_positions(n, dx):
    """x_i (µm) in DFT order: 0, δx, …, then the negative half."""
    i = np.arange(n)
    return np.where(i < (n + 1) // 2, i, i - n) * dx


def modulated_counts(inputs, calibrator=False):
    """m_i (photons) of the stated source, or of its calibrator (point
    source, no phase, visibility 1), noise- and piston-free."""
    lo, hi = band_edges(inputs)
    t, w = np.polynomial.legendre.leggauss(BAND_NODES)
    sigma = 0.5 * (hi - lo) * t + 0.5 * (hi + lo)
    # dσ = (σ_max − σ_min)/2 dt times W = 1/(σ_max − σ_min).
    weight = w / 2.0
    dx = float(inputs["dx_um"])
    amplitude = weight.astype(np.complex128)
    if not calibrator:
        sigma0, width = 0.5 * (lo + hi), hi - lo
        d = 8.0 * float(inputs["dispersion_pp_rad"]) / width**2
        phase = 0.5 * d * (sigma - sigma0) ** 2
        amplitude = amplitude * source_visibility(inputs, sigma) * np.exp(1j * phase)
    if inputs["integrating"]:
        amplitude = amplitude * np.sinc(sigma * dx)
    x = sample_positions(int(inputs["samples"]), dx)
    fringe = (np.exp(2j * np.pi * np.outer(x, sigma)) @ amplitude).real
    scale = 1.0 if calibrator else float(inputs["visibility"])
    return float(inputs["photons"]) * scale * fringe


def model_from_inputs(inputs, window):
    """(continuum c_i, mean counts n_i, bins K, calibration (C1, C2)) from
    the stated physical inputs."""
    n = int(inputs["samples"])
    continuum = np.full(n, float(inputs["photons"]))
    mean_counts = continuum + modulated_counts(inputs)
    lo, hi = band_edges(inputs)
    bins = window_bins(n, window, float(inputs["dx_um"]), (lo, hi))
    b = np.fft.fft(modulated_counts(inputs, calibrator=True))[bins]
    calibration = (float(np.sum(np.abs(b) ** 2)), float(np.abs(np.sum(b)) ** 2))
    return continuum, mean_counts, bins, calibration


def model_from_sidecar(sidecar, window):
    """The same four, read from what v2ref wrote in the sidecar."""
    continuum = np.asarray(sidecar["continuum_photons"], dtype=np.float64)
    mean_counts = np.asarray(sidecar["mean_counts_photons"], dtype=np.float64)
    entry = window_entry(sidecar, window)
    bins = np.asarray(entry["bin_indices"], dtype=np.int64)
    cal = entry["calibration"]
    return continuum, mean_counts, bins, (cal["v1_sq"], cal["v2_sq"])


def window_bins(n, window, dx, band):
    """The bins K a window sums, for N = n samples at δx over the band."""
    positive = np.arange(1, (n + 1) // 2)  # 1 … ⌈N/2⌉ − 1
    if window == "positive":
        return positive
    if window == "all":
        return np.arange(n)
    if window == "band":
        # The edges in units of bins, each widened by 1e-9 of itself: a bin
        # exactly on an edge is kept whatever the rounding (conventions §6).
        lo, hi = n * dx * band[0], n * dx * band[1]
        return positive[(positive >= lo - 1e-9 * abs(lo)) & (positive <= hi + 1e-9 * abs(hi))]
    raise ValueError(f"unknown window {window!r}")


def v2_bias_weights(n, bins):
    """|u_i|² with u_i = Σ_{k∈K} exp(−2πi ik/N), i = 0 … N−1."""
    i = np.arange(n)
    # Reduce ik modulo N before scaling, so the phase stays exact for large N.
    phase = -2.0 * np.pi * (np.outer(i, bins) % n) / n
    u = np.exp(1j * phase).sum(axis=1)
    return np.abs(u) ** 2


def estimate(sidecar, rows, window="positive", bias="model", mistake="none", model="inputs"):
    """Normalized (V1², V2²) of every row: two arrays of length rows."""
    inputs = sidecar["inputs"]
    n = rows.shape[1]
    if model == "inputs":
        continuum, mean_counts, bins, cal = model_from_inputs(inputs, window)
    elif model == "sidecar":
        continuum, mean_counts, bins, cal = model_from_sidecar(sidecar, window)
    else:
        raise ValueError(f"unknown model {model!r}")
    read_var = float(inputs["read_noise"]) ** 2
    photon = bool(inputs["photon_noise"])

    # Modulated samples M_i.
    m_rows = rows if sidecar["continuum_subtracted"] else rows - continuum

    # Raw estimates over the window.
    b = np.fft.fft(m_rows, axis=1)[:, bins]
    v1_raw = np.sum(np.abs(b) ** 2, axis=1)
    v2_raw = np.abs(np.sum(b, axis=1)) ** 2

    # Per-sample noise variance v_i (one row of it per interferogram).
    if not photon:
        variance = np.full_like(m_rows, read_var)
    elif mistake == "photon-bias-from-m":
        variance = np.broadcast_to(read_var + (mean_counts - continuum), m_rows.shape)
    elif bias == "model":
        variance = np.broadcast_to(read_var + mean_counts, m_rows.shape)
    elif bias == "counts":
        variance = read_var + (continuum + m_rows)
    else:
        raise ValueError(f"unknown bias convention {bias!r}")

    b1 = len(bins) * variance.sum(axis=1)
    b2 = variance @ v2_bias_weights(n, bins)

    v1 = v1_raw - b1
    v2 = v2_raw - b2
    if mistake != "no-calibration":
        v1 = v1 / cal[0]
        v2 = v2 / cal[1]
    return v1, v2


def write_csv(path, v1, v2):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["row", "v1_sq", "v2_sq"])
        for r, (a, b) in enumerate(zip(v1.tolist(), v2.tolist())):
            w.writerow([r, repr(a), repr(b)])


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("sidecar", help="the set's JSON sidecar (v2ref synth)")
    p.add_argument("--out", required=True, help="CSV file to write")
    p.add_argument("--bins", choices=WINDOWS, default="positive")
    p.add_argument("--bias", choices=BIAS_CONVENTIONS, default="model")
    p.add_argument("--mistake", choices=MISTAKES, default="none")
    p.add_argument("--model", choices=MODELS, default="inputs")
    a = p.parse_args(argv)
    try:
        sidecar, rows = load_set(a.sidecar)
        v1, v2 = estimate(sidecar, rows, a.bins, a.bias, a.mistake, a.model)
    except (OSError, ValueError, KeyError) as e:
        print(f"numpy_pipeline: {e}", file=sys.stderr)
        return 2
    if not (np.all(np.isfinite(v1)) and np.all(np.isfinite(v2))):
        print("numpy_pipeline: non-finite estimate", file=sys.stderr)
    write_csv(a.out, v1, v2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
