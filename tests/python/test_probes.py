"""Hostile but realistic calls of the Python package (issue 28): wrong
dtypes, non-contiguous and read-only arrays, huge claimed shapes, unknown
keys, meaningless sizes. Each ends as a result or a ValueError/TypeError
naming the argument, quickly and without a copy of the claimed size.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

import v2ref

N = 16


@pytest.fixture(scope="module")
def small_set():
    rows, sc = v2ref.synthesize(rows=8, samples=N, reference_blocks=0, seed=3)
    return np.asarray(rows), sc


@pytest.mark.parametrize(
    "bad",
    [
        np.zeros((4, N), dtype=complex),
        np.zeros((4, N), dtype=object),
        np.zeros((4, N), dtype=bool),
        np.array([["a"] * N] * 4),
        np.zeros((4, N, 2, 1)),
        np.zeros(N),
    ],
    ids=["complex", "object", "bool", "str", "4-D", "1-D"],
)
def test_wrong_arrays_are_refused_by_name(bad):
    with pytest.raises(TypeError, match="interferograms"):
        v2ref.estimate(bad)


def test_a_3d_array_without_channels_is_refused_by_name():
    # (rows, C, N) is a dispersed set's shape: here N channels of 2
    # samples, which a wide-band configuration refuses by value.
    with pytest.raises(ValueError, match="^interferograms: 16 channels .*C = 1"):
        v2ref.estimate(np.zeros((4, N, 2)))


def test_non_contiguous_and_read_only_arrays_give_the_same_answer(small_set):
    rows, sc = small_set
    ref = v2ref.estimate(rows, sidecar=sc)
    wide = np.zeros((rows.shape[0], 2 * N))
    wide[:, ::2] = rows
    ro = rows.copy()
    ro.flags.writeable = False
    for x in (wide[:, ::2], ro, np.asfortranarray(rows), rows.astype(np.float32).astype(np.float64)):
        got = v2ref.estimate(x, sidecar=sc)
        assert np.array_equal(got["v2_sq"], ref["v2_sq"])


def test_a_huge_claimed_shape_is_refused_before_any_copy():
    # A zero-stride view claiming 10^9 rows: 119 GiB as float64.
    huge = np.broadcast_to(np.float32(1.0), (10**9, N))
    t = time.perf_counter()
    with pytest.raises(ValueError, match="interferograms.*GiB"):
        v2ref.estimate(huge)
    assert time.perf_counter() - t < 1.0


def test_score_checks_the_rows_before_copying(small_set):
    _, sc = small_set
    huge = np.broadcast_to(np.float32(0.0), (10**9,))
    t = time.perf_counter()
    with pytest.raises(ValueError, match="estimates.*rows"):
        v2ref.score({"v2_sq": huge}, sc)
    with pytest.raises(ValueError, match="estimates.*rows"):
        v2ref.score(np.broadcast_to(np.float32(0.0), (10**9, 2)), sc)
    assert time.perf_counter() - t < 1.0


def test_score_refuses_an_unknown_key(small_set):
    rows, sc = small_set
    est = v2ref.estimate(rows, sidecar=sc)
    with pytest.raises(ValueError, match="estimates.*'V1_sq'"):
        v2ref.score({"V1_sq": est["v1_sq"], "v2_sq": est["v2_sq"]}, sc)
    # estimate's own answer is accepted whole.
    assert "pass" in v2ref.score(est, sc)


def test_meaningless_sizes_are_refused_with_the_reason(small_set):
    rows, sc = small_set
    with pytest.raises(ValueError, match="trials"):
        v2ref.simulate(trials=2)
    with pytest.raises(ValueError, match="alpha"):
        v2ref.score(v2ref.estimate(rows, sidecar=sc), sc, alpha=1e-20)
    with pytest.raises(ValueError, match="no light"):
        v2ref.estimate(np.zeros((3, N)))
    with pytest.raises(ValueError, match="aperture_m"):
        v2ref.piston(aperture_m=1e300, scans=4)
