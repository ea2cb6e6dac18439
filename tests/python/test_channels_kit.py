"""The dispersed conformance kit from Python (issue 54): ``synthesize``
with ``channels=`` returns rows (rows, C, N) and a sidecar with
``channels``; ``estimate`` returns (rows, C) arrays; ``score`` takes them
and answers per channel and for the whole set. One channel keeps today's
shapes and bits; wrong shapes are a ValueError naming the argument and the
expected shape.
"""

import json

import numpy as np
import pytest

import v2ref

C, N = 6, 256
SMALL = dict(channels=C, samples=N, rows=64, seed=5, reference_blocks=0, photons=200.0)


@pytest.fixture(scope="module")
def small():
    return v2ref.synthesize(**SMALL)


def test_shapes_of_a_dispersed_set_its_estimates_and_score(small):
    rows, sc = small
    assert rows.shape == (64, C, N) and rows.dtype == np.float64
    assert sc["data"]["channels"] == C and len(sc["channels"]) == C
    est = v2ref.estimate(rows, sidecar=sc)
    assert set(est) == set(v2ref.ESTIMATE_COLUMNS)
    assert all(v.shape == (64, C) for v in est.values())
    # Channel j's column is channel j's rows estimated alone with the same
    # configuration by keywords: the two routes agree to the bit.
    kw = v2ref.estimate(rows, channels=C, photons=200.0)
    for k in est:
        assert np.array_equal(kw[k], est[k]), k
    report = v2ref.score({"v1_sq": est["v1_sq"], "v2_sq": est["v2_sq"]}, sc)
    assert set(report) >= {"alpha", "tests", "z_crit", "channels", "pass", "rows", "bins", "bias"}
    assert len(report["channels"]) == C and report["tests"] == 4 * C
    assert report["rows"] == 64


def test_rows_are_deterministic_whatever_the_threads(small):
    rows, _ = small
    again, _ = v2ref.synthesize(**SMALL, threads=1)
    assert np.array_equal(rows, again)


def test_one_channel_is_todays_answer():
    wide, _ = v2ref.synthesize(samples=N, rows=32, seed=3, reference_blocks=0)
    one, sc = v2ref.synthesize(channels=1, samples=N, rows=32, seed=3, reference_blocks=0)
    assert one.shape == wide.shape == (32, N)
    assert np.array_equal(one, wide)
    got = v2ref.estimate(one, sidecar=sc)
    want = v2ref.estimate(wide)
    for k in want:
        assert got[k].shape == (32,)
        assert np.array_equal(got[k], want[k]), k
    # Given as (rows, 1, N), the estimates keep the channel axis.
    three = v2ref.estimate(one[:, None, :], sidecar=sc)
    assert three["v1_sq"].shape == (32, 1)
    assert np.array_equal(three["v1_sq"][:, 0], want["v1_sq"])


def test_wrong_shapes_name_the_argument_and_the_shape(small):
    rows, sc = small
    with pytest.raises(ValueError, match=r"^interferograms: .*\(rows, 6, N\)"):
        v2ref.estimate(rows.reshape(64, C * N), sidecar=sc)
    with pytest.raises(ValueError, match=r"^interferograms: 3 channels .*\(rows, 6, N\)"):
        v2ref.estimate(rows[:, :3, :], sidecar=sc)
    with pytest.raises(ValueError, match=r"^interferograms: 6 channels .*C = 1"):
        v2ref.estimate(rows)
    with pytest.raises(ValueError, match=r"^calibrator: shape"):
        v2ref.estimate(rows, sidecar=sc, calibrator=rows[:, 0, :])
    est = v2ref.estimate(rows, sidecar=sc)
    with pytest.raises(ValueError, match=r"^estimates: v1_sq has 3 columns.*\(rows, 6\)"):
        v2ref.score({"v1_sq": est["v1_sq"][:, :3]}, sc)
    with pytest.raises(ValueError, match=r"^estimates: 1-D arrays; the set has C = 6 channels"):
        v2ref.score({"v1_sq": est["v1_sq"][:, 0]}, sc)
    with pytest.raises(ValueError, match=r"^estimates: 32 rows; the sidecar's set has 64"):
        v2ref.score({"v1_sq": est["v1_sq"][:32]}, sc)
    bad = est["v2_sq"].copy()
    bad[3, 2] = np.nan
    with pytest.raises(ValueError, match=r"^estimates: row 4 \(1-based\), column v2_sq, channel 3"):
        v2ref.score({"v2_sq": bad}, sc)
    wide_rows, wide_sc = v2ref.synthesize(samples=N, rows=8, reference_blocks=0)
    w = v2ref.estimate(wide_rows, sidecar=wide_sc)
    with pytest.raises(ValueError, match=r"^estimates: \(rows, C\) arrays, but the set is wide-band"):
        v2ref.score({"v1_sq": w["v1_sq"][:, None]}, wide_sc)


def test_out_writes_the_set_as_rows_c_n(tmp_path, small):
    rows, sc = small
    again, sc2 = v2ref.synthesize(**SMALL, out=tmp_path / "set")
    assert np.array_equal(np.load(tmp_path / "set.npy"), again)
    assert np.load(tmp_path / "set.npy").shape == (64, C, N)
    on_disk = json.loads((tmp_path / "set.json").read_text())
    assert on_disk["data"]["npy"] == "set.npy" and on_disk["data"]["channels"] == C
    # The sidecar on disk is read back as the dict was: same estimates.
    a = v2ref.estimate(again, sidecar=tmp_path / "set.json")
    b = v2ref.estimate(rows, sidecar=sc)
    assert np.array_equal(a["v2_sq"], b["v2_sq"])


def test_client_or_checkpoint_still_refuse_channels(tmp_path):
    with pytest.raises(ValueError, match="^channels: not taken by `synthesize with client or checkpoint`"):
        v2ref.synthesize(**SMALL, checkpoint=tmp_path / "ck")


def test_the_docs_dispersed_route_runs_as_written(tmp_path, monkeypatch):
    """docs/python.md's dispersed block, run as written: a correct set
    passes per channel, through arrays and through an astropy-written
    OIFITS file of NWAVE = 6 (decreasing float32 EFF_WAVE)."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "docs" / "python.md").read_text()
    start = text.index("# dispersed route")
    block = text[start : text.index("```", start)]
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(block, "docs/python.md", "exec"), scope)
    assert scope["report"]["pass"] and len(scope["report"]["channels"]) == 6
    table = scope["table"]
    assert table["vis2data"].shape == table["vis2err"].shape == table["flag"].shape == (2000, 6)
    assert np.all(np.diff(table["eff_wave_m"]) < 0)
    # Read back in the set's order, the file's values are the estimates.
    assert np.array_equal(scope["back"], scope["est"]["v2_sq"])
    assert v2ref.score({"v2_sq": scope["back"]}, scope["sidecar"])["pass"]
    with pytest.raises(ValueError, match=r"^sidecar: a dispersed set of C = 6"):
        v2ref.score("dispersed.fits", scope["sidecar"])


def test_a_calibrator_normalizes_each_channel_by_its_own_rows(small):
    """With the counts bias (the row's own counts, so the same bias for
    the rows and the calibrator) and the rows as their own calibrator,
    each channel's mean V1² and V2² is 1: channel j is divided by channel
    j's mean, not the whole band's or another channel's."""
    rows, sc = small
    est = v2ref.estimate(rows, sidecar=sc, bias="counts", calibrator=rows)
    assert est["v1_sq"].shape == (64, C)
    # tol: a mean of 64 ratios against the same sum, rounding only
    np.testing.assert_allclose(est["v1_sq"].mean(axis=0), 1.0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(est["v2_sq"].mean(axis=0), 1.0, rtol=0, atol=1e-12)  # tol: as above
