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
    band       the sidecar's truth.windows[bins == "band"].bin_indices

The additive-noise bias is subtracted with v_i the noise variance of sample i:

    b1 = |K| Σ_i v_i
    b2 = Σ_i |u_i|² v_i,    u_i = Σ_{k∈K} exp(−2πi ik/N)

    v_i = σ_det² + n_i   with photon noise,   σ_det² without

where n_i is the sample's mean count, taken (``--bias``) from the model
(``model``: n_i = ``mean_counts_photons[i]``) or from the row itself
(``counts``: n_i = c_i + M_i). The normalized estimates are
(raw − bias) / C, C being the sidecar's ``calibration`` of the window
(the calibrator's noise-free raw V1² and V2²).

``--mistake`` deliberately gets one thing wrong, to check that a scorer
catches it:

    photon-bias-from-m   v_i = σ_det² + m_i (the model's modulated part,
                         m_i = mean_counts − continuum) instead of n_i
    no-calibration       no division by C

Output: CSV with header ``row,v1_sq,v2_sq``, one line per row (0-based row
index), floats written with repr() so they round-trip exactly.

Usage:
    python numpy_pipeline.py SET.json --out EST.csv [--bins positive|band|all]
                             [--bias model|counts] [--mistake ...]
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


def window_bins(n, window, sidecar):
    """The bins K a window sums, for N = n samples."""
    if window == "positive":
        return np.arange(1, (n + 1) // 2)  # 1 … ⌈N/2⌉ − 1
    if window == "all":
        return np.arange(n)
    if window == "band":
        return np.asarray(window_entry(sidecar, "band")["bin_indices"], dtype=np.int64)
    raise ValueError(f"unknown window {window!r}")


def v2_bias_weights(n, bins):
    """|u_i|² with u_i = Σ_{k∈K} exp(−2πi ik/N), i = 0 … N−1."""
    i = np.arange(n)
    # Reduce ik modulo N before scaling, so the phase stays exact for large N.
    phase = -2.0 * np.pi * (np.outer(i, bins) % n) / n
    u = np.exp(1j * phase).sum(axis=1)
    return np.abs(u) ** 2


def estimate(sidecar, rows, window="positive", bias="model", mistake="none"):
    """Normalized (V1², V2²) of every row: two arrays of length rows."""
    inputs = sidecar["inputs"]
    n = rows.shape[1]
    continuum = np.asarray(sidecar["continuum_photons"], dtype=np.float64)
    mean_counts = np.asarray(sidecar["mean_counts_photons"], dtype=np.float64)
    read_var = float(inputs["read_noise"]) ** 2
    photon = bool(inputs["photon_noise"])

    # Modulated samples M_i.
    m_rows = rows if sidecar["continuum_subtracted"] else rows - continuum

    # Raw estimates over the window.
    bins = window_bins(n, window, sidecar)
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
        cal = window_entry(sidecar, window)["calibration"]
        v1 = v1 / cal["v1_sq"]
        v2 = v2 / cal["v2_sq"]
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
    a = p.parse_args(argv)
    try:
        sidecar, rows = load_set(a.sidecar)
        v1, v2 = estimate(sidecar, rows, a.bins, a.bias, a.mistake)
    except (OSError, ValueError, KeyError) as e:
        print(f"numpy_pipeline: {e}", file=sys.stderr)
        return 2
    if not (np.all(np.isfinite(v1)) and np.all(np.isfinite(v2))):
        print("numpy_pipeline: non-finite estimate", file=sys.stderr)
    write_csv(a.out, v1, v2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
