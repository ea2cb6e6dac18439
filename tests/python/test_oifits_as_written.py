"""OIFITS files as the field writes and edits them, read by v2ref.

Issue 53: checksums verified HDU by HDU where an HDU has them (a GRAVITY
product's appended HDU carries none), a v2ref file edited with astropy
(an HDU removed or added, checksums rewritten), a target written with a
leading blank (MIRC-X), refusals naming EXTNAME and INSNAME, OI_ARRAY's
DIAMETER. Issue 54: every row's UCOORD, VCOORD, MJD, TARGET_ID and every
table's wavelengths read from files of several channels per row, against
astropy's values. Every file here is written or edited with astropy.

Environment: V2REF_BIN, the v2ref binary (default target/release/v2ref).
"""

import warnings

import numpy as np
import pytest
from astropy.io import fits

import v2ref
from test_oifits import run

ROWS = 48
pytestmark = pytest.mark.needs_bin


@pytest.fixture(scope="module")
def set_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("as_written")
    run("synth", "--out", d / "set", "--rows", ROWS, "--samples", 32, "--source", "point",
        "--visibility", 0.6, "--photons", 30, "--reference-blocks", 8, "--quiet", "--oifits")
    run("estimate", "--sidecar", d / "set.json", "--out", d / "est.fits")
    run("estimate", "--sidecar", d / "set.json", "--out", d / "est.csv")
    return d


def read_noting(path, **kw):
    """read_oifits's tables and the notes it issued as warnings."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tables = v2ref.read_oifits(path, **kw)
    return tables, [str(w.message) for w in caught if issubclass(w.category, UserWarning)]


def gravity_like(path, with_checksums=True):
    """A pipeline product signed HDU by HDU, then an HDU appended later
    without CHECKSUM or DATASUM (as GRAVITY's products are)."""
    n, nwave = 4, 3
    prim = fits.PrimaryHDU()
    prim.header["CONTENT"] = "OIFITS2"
    tgt = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=[1]), fits.Column("TARGET", "16A", array=["HD 1"]),
    ], name="OI_TARGET")
    wav = fits.BinTableHDU.from_columns([
        fits.Column("EFF_WAVE", "E", unit="m", array=[2.0e-6, 2.2e-6, 2.4e-6]),
        fits.Column("EFF_BAND", "E", unit="m", array=[1e-7, 1e-7, 1e-7]),
    ], name="OI_WAVELENGTH")
    vis2 = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=np.ones(n)),
        fits.Column("MJD", "D", array=60000 + np.arange(n) / 1440),
        fits.Column("VIS2DATA", f"{nwave}D", array=np.full((n, nwave), 0.5)),
        fits.Column("VIS2ERR", f"{nwave}D", array=np.full((n, nwave), 0.01)),
        fits.Column("UCOORD", "D", array=np.full(n, 30.0)),
        fits.Column("VCOORD", "D", array=np.full(n, 5.0)),
        fits.Column("FLAG", f"{nwave}L", array=np.zeros((n, nwave), bool)),
    ], name="OI_VIS2")
    for x in (tgt, wav, vis2):
        x.header["OI_REVN"] = 2
    for x in (wav, vis2):
        x.header["INSNAME"] = "GRAVITY_SC"
    fits.HDUList([prim, tgt, wav, vis2]).writeto(path, checksum=with_checksums)
    extra = fits.BinTableHDU.from_columns([fits.Column("X", "D", array=[1.0])], name="OI_FLUX_LATER")
    fits.append(path, extra.data, extra.header, checksum=False)


def test_an_appended_hdu_without_checksums_is_read_and_named(tmp_path):
    path = tmp_path / "gravity.fits"
    gravity_like(path)
    with fits.open(path) as h:
        assert "CHECKSUM" in h[3].header and "CHECKSUM" not in h[4].header
    tables, notes = read_noting(path)
    assert [t["insname"] for t in tables] == ["GRAVITY_SC"]
    np.testing.assert_array_equal(tables[0]["vis2data"], np.full((4, 3), 0.5))
    assert len(notes) == 1 and "OI_FLUX_LATER" in notes[0] and "no CHECKSUM" in notes[0], notes


def test_an_unsigned_file_gets_no_note_and_a_damaged_signed_hdu_is_still_refused(tmp_path):
    plain = tmp_path / "plain.fits"
    gravity_like(plain, with_checksums=False)
    assert read_noting(plain)[1] == []
    damaged = tmp_path / "damaged.fits"
    gravity_like(damaged)
    with fits.open(damaged) as h:
        start = h[3].fileinfo()["datLoc"]
    raw = bytearray(damaged.read_bytes())
    raw[start + 5] ^= 0x40
    damaged.write_bytes(bytes(raw))
    with pytest.raises(ValueError) as e:
        v2ref.read_oifits(damaged)
    msg = str(e.value)
    assert "EXTNAME OI_VIS2" in msg and "INSNAME GRAVITY_SC" in msg, msg
    assert "DATASUM and CHECKSUM do not match" in msg, msg


def edit(src, dst, remove=(), add=False):
    """``src`` as astropy rewrites it: HDUs removed by EXTNAME, an HDU
    appended, every checksum recomputed."""
    with fits.open(src) as h:
        keep = [x for x in h if x.name not in remove]
        if add:
            keep.append(fits.BinTableHDU.from_columns([fits.Column("X", "D", array=[1.0])], name="NOTES"))
        fits.HDUList(keep).writeto(dst, checksum=True)


@pytest.mark.parametrize("change", [
    {"remove": ("OI_ARRAY",)}, {"add": True}, {"remove": ("OI_TARGET", "OI_ARRAY"), "add": True},
])
def test_a_v2ref_file_edited_with_astropy_is_read_with_a_note(set_dir, tmp_path, change):
    edited = tmp_path / "edited.fits"
    edit(set_dir / "est.fits", edited, **change)
    tables, notes = read_noting(edited)
    original = v2ref.read_oifits(set_dir / "est.fits")
    assert [t["insname"] for t in tables] == ["V2REF_V1SQ", "V2REF_V2SQ"]
    for a, b in zip(tables, original):
        np.testing.assert_array_equal(a["vis2data"], b["vis2data"])
    held = 7 - len(change.get("remove", ())) + change.get("add", 0)
    assert len(notes) == 1 and f"written with 7 HDUs and holds {held}" in notes[0], notes
    assert ("HDUs were added" if held > 7 else "HDUs were removed") in notes[0], notes
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        got = v2ref.score_oifits(edited, sidecar=set_dir / "set.json")
        want = v2ref.score_oifits(set_dir / "est.fits", sidecar=set_dir / "set.json")
    assert got == {**want, "estimates": str(edited)}


def test_a_v2ref_file_whose_last_hdu_is_gone_is_refused_as_possibly_truncated(set_dir, tmp_path):
    cut = tmp_path / "cut.fits"
    with fits.open(set_dir / "est.fits") as h:
        fits.HDUList(list(h)[:-1]).writeto(cut, checksum=True)
    with pytest.raises(ValueError) as e:
        v2ref.read_oifits(cut)
    msg = str(e.value)
    assert "holds the first 6" in msg and "truncated" in msg and "set V2R_NHDU to 6" in msg, msg


def two_targets(path, v2, first_name=" bet Ari"):
    """A pipeline's file (astropy) whose first target's name starts with
    a blank, as the MIRC-X pipeline writes it: that target's rows are
    ``v2``, then three rows of a second target."""
    n = len(v2) + 3
    ids = np.r_[np.ones(len(v2)), np.full(3, 2)]
    prim = fits.PrimaryHDU()
    tgt = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=[1, 2]),
        fits.Column("TARGET", "16A", array=[first_name, "HD 2"]),
    ], name="OI_TARGET")
    wav = fits.BinTableHDU.from_columns([
        fits.Column("EFF_WAVE", "E", array=[2.2e-6]), fits.Column("EFF_BAND", "E", array=[4e-7]),
    ], name="OI_WAVELENGTH")
    vis2 = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=ids),
        fits.Column("MJD", "D", array=60000 + np.arange(n) / 1440),
        fits.Column("VIS2DATA", "D", array=np.r_[v2, np.full(3, 0.9)]),
        fits.Column("VIS2ERR", "D", array=np.full(n, 0.1)),
        fits.Column("UCOORD", "D", array=np.arange(n, dtype=float)),
        fits.Column("VCOORD", "D", array=-np.arange(n, dtype=float)),
        fits.Column("FLAG", "L", array=np.zeros(n, bool)),
    ], name="OI_VIS2")
    for x in (tgt, wav, vis2):
        x.header["OI_REVN"] = 1
    for x in (wav, vis2):
        x.header["INSNAME"] = "MIRCX"
    fits.HDUList([prim, tgt, wav, vis2]).writeto(path)


def test_a_target_written_with_a_leading_blank_is_chosen_by_its_name(set_dir, tmp_path):
    est = np.genfromtxt(set_dir / "est.csv", delimiter=",", names=True)
    path = tmp_path / "mircx.fits"
    two_targets(path, est["v2_sq"])
    with fits.open(path) as h:
        assert h["OI_TARGET"].data["TARGET"][0] == " bet Ari"
    for name in ("bet Ari", " bet Ari ", "BET ARI"):
        got = v2ref.score_oifits(path, sidecar=set_dir / "set.json", estimator="v2_sq", target=name)
        assert got["rows"] == ROWS, name
        tables = v2ref.read_oifits(path, target=name)
        np.testing.assert_array_equal(tables[0]["vis2data"][:, 0], est["v2_sq"])


def test_estimate_and_truth_files_say_the_aperture_or_that_it_is_unknown(set_dir, tmp_path):
    with fits.open(set_dir / "set.truth.fits") as h:
        # No piston: the set has no aperture; NaN says so (FITS's undefined float).
        assert np.isnan(h["OI_ARRAY"].data["DIAMETER"]).all()
        assert np.isnan(h["OI_ARRAY"].data["FOV"]).all()
    run("synth", "--out", tmp_path / "p", "--rows", 4, "--samples", 64, "--fringe-hz", 300,
        "--aperture-m", 1.8, "--quiet", "--oifits")
    run("estimate", "--sidecar", tmp_path / "p.json", "--out", tmp_path / "p_est.fits")
    for name in ("p.truth.fits", "p_est.fits"):
        with fits.open(tmp_path / name) as h:
            # DIAMETER is float32 (TFORM E), as the standard writes it.
            np.testing.assert_array_equal(h["OI_ARRAY"].data["DIAMETER"], np.float32([1.8, 1.8]))
            assert np.isfinite(h["OI_ARRAY"].data["FOV"]).all() and (h["OI_ARRAY"].data["FOV"] > 0).all()


# Issue 54: OIFITS read as the field writes it.


def dispersed(path):
    """Two instruments (astropy): PIONIER-like, 3 channels per row, rows of
    two targets; and a second INSNAME of one channel."""
    prim = fits.PrimaryHDU()
    tgt = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=[1, 2]), fits.Column("TARGET", "16A", array=["alf Boo", "HD 2"]),
    ], name="OI_TARGET")
    hdus = [prim, tgt]
    rng = np.random.default_rng(5)
    for ins, waves, n in (("PIONIER", [1.6e-6, 1.7e-6, 1.8e-6], 6), ("SINGLE", [2.2e-6], 2)):
        nw = len(waves)
        wav = fits.BinTableHDU.from_columns([
            fits.Column("EFF_WAVE", "E", array=waves),
            fits.Column("EFF_BAND", "E", array=np.linspace(4e-8, 6e-8, nw)),
        ], name="OI_WAVELENGTH")
        vis2 = fits.BinTableHDU.from_columns([
            fits.Column("TARGET_ID", "I", array=[1, 2, 1, 2, 1, 2][:n]),
            fits.Column("MJD", "D", array=58000.25 + np.arange(n) / 3600),
            fits.Column("VIS2DATA", f"{nw}D", array=rng.uniform(0, 1, (n, nw))),
            fits.Column("VIS2ERR", f"{nw}D", array=rng.uniform(0.01, 0.1, (n, nw))),
            fits.Column("UCOORD", "D", array=rng.uniform(-100, 100, n)),
            fits.Column("VCOORD", "D", array=rng.uniform(-100, 100, n)),
            fits.Column("FLAG", f"{nw}L", array=rng.uniform(0, 1, (n, nw)) < 0.2),
        ], name="OI_VIS2")
        for x in (wav, vis2):
            x.header["INSNAME"] = ins
            x.header["OI_REVN"] = 2
        hdus += [wav, vis2]
    tgt.header["OI_REVN"] = 2
    fits.HDUList(hdus).writeto(path)


def astropy_tables(path):
    with fits.open(path) as h:
        waves = {x.header["INSNAME"]: x.data for x in h if x.name == "OI_WAVELENGTH"}
        return [(x.header["INSNAME"], x.data.copy(), waves[x.header["INSNAME"]].copy())
                for x in h if x.name == "OI_VIS2"]


def test_rows_and_channels_are_read_as_astropy_reads_them(tmp_path):
    path = tmp_path / "dispersed.fits"
    dispersed(path)
    tables = v2ref.read_oifits(path)
    want = astropy_tables(path)
    assert [t["insname"] for t in tables] == [w[0] for w in want]
    for t, (ins, d, w) in zip(tables, want):
        nw = len(w)
        np.testing.assert_array_equal(t["eff_wave_m"], w["EFF_WAVE"].astype(np.float64))
        np.testing.assert_array_equal(t["eff_band_m"], w["EFF_BAND"].astype(np.float64))
        np.testing.assert_array_equal(t["target_id"], d["TARGET_ID"])
        for key, col in (("mjd", "MJD"), ("ucoord_m", "UCOORD"), ("vcoord_m", "VCOORD")):
            np.testing.assert_array_equal(t[key], d[col])
        for key, col in (("vis2data", "VIS2DATA"), ("vis2err", "VIS2ERR"), ("flag", "FLAG")):
            np.testing.assert_array_equal(t[key], np.asarray(d[col]).reshape(len(d), nw))
        assert t["vis2data"].shape == (len(d), nw), ins


def test_tables_and_rows_are_chosen_by_insname_and_target_as_score_chooses(tmp_path):
    path = tmp_path / "dispersed.fits"
    dispersed(path)
    want = {ins: d for ins, d, _ in astropy_tables(path)}
    only = v2ref.read_oifits(path, insname=" PIONIER")
    assert [t["insname"] for t in only] == ["PIONIER"]
    for target, tid in (("HD 2", 2), ("1", 1)):
        chosen = v2ref.read_oifits(path, insname="PIONIER", target=target)
        d = want["PIONIER"][want["PIONIER"]["TARGET_ID"] == tid]
        assert len(chosen) == 1 and (chosen[0]["target_id"] == tid).all()
        np.testing.assert_array_equal(chosen[0]["ucoord_m"], d["UCOORD"])
        np.testing.assert_array_equal(chosen[0]["vis2data"], d["VIS2DATA"])
    # SINGLE has rows of target 1 only (its 2 rows: ids 1, 2): both tables keep theirs.
    both = v2ref.read_oifits(path, target="alf Boo")
    assert [len(t["mjd"]) for t in both] == [3, 1]
    with pytest.raises(ValueError, match="insname: NIRISS: no OI_VIS2 table of this INSNAME; the file has PIONIER, SINGLE"):
        v2ref.read_oifits(path, insname="NIRISS")
    with pytest.raises(ValueError, match="target: Vega: no OI_VIS2 row of this target"):
        v2ref.read_oifits(path, target="Vega")
    with pytest.raises(TypeError, match="target: 3 is not a string"):
        v2ref.read_oifits(path, target=3)

