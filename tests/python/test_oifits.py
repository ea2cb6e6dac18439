"""OIFITS checked by the field's readers.

Every file v2ref writes (``estimate --out FILE.fits``, ``synth --oifits``,
``plan --oifits``, and the package's ``write_oifits``/``write_oifits_truth``)
is read by astropy and checked against the mandatory tables, columns,
formats, units and keywords of OIFITS v2 (Duvert, Young & Hummel 2017,
A&A 597, A8, tables 4-11), and loaded by the ``oifits`` package (an
independent OIFITS reader from PyPI). A file written here with astropy
alone, by the standard, is scored by ``v2ref score`` with the same verdict
as the same numbers in CSV.

Environment: V2REF_BIN, the v2ref binary (default target/release/v2ref).
"""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits

import v2ref

oifits_pkg = pytest.importorskip("oifits")

ROOT = Path(__file__).resolve().parents[2]
ROWS = 240

# Every test here reads files the binary writes (missing binary: CI fails,
# a local run skips saying why; conftest.py).
pytestmark = pytest.mark.needs_bin


def v2ref_bin():
    b = Path(os.environ.get("V2REF_BIN", "target/release/v2ref"))
    return b if b.is_absolute() else ROOT / b


def run(*args, code=0):
    p = subprocess.run([str(v2ref_bin()), *map(str, args)], capture_output=True, text=True)
    assert p.returncode == code, (args, p.stderr)
    return p


# The standard's mandatory columns: name -> (TFORM letter, unit or None).
# NWAVE-dimensioned columns are marked with a repeat of "NWAVE".
TARGET = {
    "TARGET_ID": ("I", None), "TARGET": ("A", None), "RAEP0": ("D", "deg"),
    "DECEP0": ("D", "deg"), "EQUINOX": ("E", "yr"), "RA_ERR": ("D", "deg"),
    "DEC_ERR": ("D", "deg"), "SYSVEL": ("D", "m/s"), "VELTYP": ("A", None),
    "VELDEF": ("A", None), "PMRA": ("D", "deg/yr"), "PMDEC": ("D", "deg/yr"),
    "PMRA_ERR": ("D", "deg/yr"), "PMDEC_ERR": ("D", "deg/yr"),
    "PARALLAX": ("E", "deg"), "PARA_ERR": ("E", "deg"), "SPECTYP": ("A", None),
}
ARRAY = {
    "TEL_NAME": ("A", None), "STA_NAME": ("A", None), "STA_INDEX": ("I", None),
    "DIAMETER": ("E", "m"), "STAXYZ": ("D", "m"), "FOV": ("D", "arcsec"),
    "FOVTYPE": ("A", None),
}
WAVELENGTH = {"EFF_WAVE": ("E", "m"), "EFF_BAND": ("E", "m")}
VIS2 = {
    "TARGET_ID": ("I", None), "TIME": ("D", "s"), "MJD": ("D", "day"),
    "INT_TIME": ("D", "s"), "VIS2DATA": ("D", None), "VIS2ERR": ("D", None),
    "UCOORD": ("D", "m"), "VCOORD": ("D", "m"), "STA_INDEX": ("I", None),
    "FLAG": ("L", None),
}
PRIMARY = ["ORIGIN", "DATE", "DATE-OBS", "CONTENT", "TELESCOP", "INSTRUME", "OBSERVER",
           "OBJECT", "INSMODE", "REFERENC", "PROG_ID", "PROCSOFT", "OBSTECH"]


def check_columns(hdu, spec):
    cols = {c.name: c for c in hdu.columns}
    for name, (letter, unit) in spec.items():
        assert name in cols, f"{hdu.name}: no {name}"
        fmt = cols[name].format
        assert fmt.endswith(letter) or letter in fmt, f"{hdu.name}.{name}: {fmt}, {letter} needed"
        if unit is not None:
            assert (cols[name].unit or "").strip() == unit, f"{hdu.name}.{name}: unit {cols[name].unit!r}"


def check_oifits2(path):
    """The mandatory structure of an OIFITS v2 file; returns the OI_VIS2 rows."""
    with fits.open(path) as h:
        h.verify("exception")
        p = h[0].header
        for k in PRIMARY:
            assert k in p, f"primary: no {k}"
        assert p["CONTENT"] == "OIFITS2"
        names = [x.name for x in h]
        for t in ("OI_TARGET", "OI_ARRAY", "OI_WAVELENGTH", "OI_VIS2"):
            assert t in names, f"no {t}"
        for x in h[1:]:
            assert x.header["OI_REVN"] == 2, x.name
        targets = {int(t) for t in h["OI_TARGET"].data["TARGET_ID"]}
        check_columns(h["OI_TARGET"], TARGET)
        arrays = {}
        for x in h:
            if x.name == "OI_ARRAY":
                check_columns(x, ARRAY)
                for k in ("ARRNAME", "FRAME", "ARRAYX", "ARRAYY", "ARRAYZ"):
                    assert k in x.header, f"OI_ARRAY: no {k}"
                arrays[x.header["ARRNAME"]] = set(int(s) for s in x.data["STA_INDEX"])
        waves = {}
        for x in h:
            if x.name == "OI_WAVELENGTH":
                check_columns(x, WAVELENGTH)
                assert x.header["INSNAME"] not in waves, "INSNAME not unique"
                waves[x.header["INSNAME"]] = len(x.data)
                assert np.all(x.data["EFF_WAVE"] > 0)
        rows = 0
        for x in h:
            if x.name != "OI_VIS2":
                continue
            check_columns(x, VIS2)
            for k in ("DATE-OBS", "ARRNAME", "INSNAME"):
                assert k in x.header, f"OI_VIS2: no {k}"
            nwave = waves[x.header["INSNAME"]]
            assert x.data["VIS2DATA"].reshape(len(x.data), -1).shape[1] == nwave
            assert x.data["FLAG"].reshape(len(x.data), -1).shape[1] == nwave
            assert set(int(t) for t in x.data["TARGET_ID"]) <= targets
            sta = arrays[x.header["ARRNAME"]]
            assert set(int(s) for s in np.ravel(x.data["STA_INDEX"])) <= sta
            assert np.all(np.asarray(x.data["VIS2ERR"]) > 0)
            rows += len(x.data)
        return rows


def load_with_oifits_package(path):
    d = oifits_pkg.open(str(path), quiet=True) if "quiet" in oifits_pkg.open.__code__.co_varnames else oifits_pkg.open(str(path))
    return len(d.vis2)


@pytest.fixture(scope="module")
def set_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("oifits")
    run("synth", "--out", d / "set", "--rows", ROWS, "--samples", 32, "--source", "point",
        "--visibility", 0.6, "--photons", 30, "--reference-blocks", 8, "--quiet", "--oifits")
    run("estimate", "--sidecar", d / "set.json", "--out", d / "est.fits")
    run("estimate", "--sidecar", d / "set.json", "--out", d / "est.csv")
    run("estimate", "--sidecar", d / "set.json", "--out", d / "v2.fits", "--oifits-estimator", "v2_sq")
    run("plan", "--quiet", "--fringe-hz", 300, "--stroke-um", 32, "--scans", 64,
        "--seeing-arcsec", 0.8, "--oifits", d / "plan.fits")
    return d


def written_files(d):
    sc = json.loads((d / "set.json").read_text())
    est = np.genfromtxt(d / "est.csv", delimiter=",", names=True)
    v2ref.write_oifits(d / "py.fits", sidecar=sc, v1_sq=est["v1_sq"], v2_sq=est["v2_sq"])
    v2ref.write_oifits_truth(d / "py_truth.fits", sidecar=d / "set.json")
    return {
        "est.fits": 2 * ROWS, "v2.fits": ROWS, "set.truth.fits": 2 * ROWS, "plan.fits": 1,
        "py.fits": 2 * ROWS, "py_truth.fits": 2 * ROWS,
    }


def test_every_written_file_passes_the_standard_and_loads_in_oifits(set_dir):
    for name, rows in written_files(set_dir).items():
        assert check_oifits2(set_dir / name) == rows, name
        assert load_with_oifits_package(set_dir / name) == rows, name


def test_plan_file_states_the_biases_to_correct(set_dir):
    with fits.open(set_dir / "plan.fits") as h:
        v = h["OI_VIS2"]
        hd = v.header
        total = hd["V2R_VMON"] + hd["V2R_BBW"] + hd["V2R_BSCN"] + hd["V2R_BPST"]
        assert v.data["VIS2DATA"][0] == pytest.approx(total, rel=1e-9)
        assert "V2R_VMON" in hd.comments["TTYPE5"]


def test_python_and_cli_write_the_same_numbers(set_dir):
    cli = v2ref.read_oifits(set_dir / "est.fits")
    py = v2ref.read_oifits(set_dir / "py.fits")
    assert [t["estimator"] for t in cli] == ["v1_sq", "v2_sq"]
    for a, b in zip(cli, py):
        np.testing.assert_array_equal(a["vis2data"], b["vis2data"])
        np.testing.assert_array_equal(a["vis2err"], b["vis2err"])
        assert a["vis2data"].shape == (ROWS, 1) and not a["flag"].any()
    est = np.genfromtxt(set_dir / "est.csv", delimiter=",", names=True)
    np.testing.assert_array_equal(cli[1]["vis2data"][:, 0], est["v2_sq"])


def astropy_oifits(path, v2, flags, eff_wave=2.2e-6):
    """An OIFITS v2 file by the standard, written with astropy alone."""
    n = len(v2)
    prim = fits.PrimaryHDU()
    for k, v in [("CONTENT", "OIFITS2"), ("ORIGIN", "test"), ("DATE", "2026-01-01"),
                 ("DATE-OBS", "2026-01-01"), ("TELESCOP", "T"), ("INSTRUME", "PIPE"),
                 ("OBSERVER", "me"), ("OBJECT", "star"), ("INSMODE", "K"), ("REFERENC", "-"),
                 ("PROG_ID", "-"), ("PROCSOFT", "astropy"), ("OBSTECH", "SCAN")]:
        prim.header[k] = v
    tgt = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=[1]), fits.Column("TARGET", "16A", array=["star"]),
    ], name="OI_TARGET")
    arr = fits.BinTableHDU.from_columns([
        fits.Column("TEL_NAME", "16A", array=["A", "B"]), fits.Column("STA_NAME", "16A", array=["A", "B"]),
        fits.Column("STA_INDEX", "I", array=[1, 2]), fits.Column("DIAMETER", "E", unit="m", array=[1, 1]),
        fits.Column("STAXYZ", "3D", unit="m", array=np.zeros((2, 3))),
    ], name="OI_ARRAY")
    arr.header["ARRNAME"] = "ARR"
    wav = fits.BinTableHDU.from_columns([
        fits.Column("EFF_WAVE", "E", unit="m", array=[eff_wave]),
        fits.Column("EFF_BAND", "E", unit="m", array=[4e-7]),
    ], name="OI_WAVELENGTH")
    wav.header["INSNAME"] = "PIPE"
    vis2 = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=np.ones(n)), fits.Column("TIME", "D", unit="s", array=np.arange(n)),
        fits.Column("MJD", "D", unit="day", array=60000 + np.arange(n) / 86400),
        fits.Column("INT_TIME", "D", unit="s", array=np.ones(n)),
        fits.Column("VIS2DATA", "1D", array=v2), fits.Column("VIS2ERR", "1D", array=np.full(n, 0.1)),
        fits.Column("UCOORD", "D", unit="m", array=np.full(n, 18.0)),
        fits.Column("VCOORD", "D", unit="m", array=np.zeros(n)),
        fits.Column("STA_INDEX", "2I", array=np.tile([1, 2], (n, 1))),
        fits.Column("FLAG", "1L", array=flags),
    ], name="OI_VIS2")
    for x in (tgt, arr, wav, vis2):
        x.header["OI_REVN"] = 2
    vis2.header["INSNAME"] = "PIPE"
    vis2.header["ARRNAME"] = "ARR"
    vis2.header["DATE-OBS"] = "2026-01-01"
    fits.HDUList([prim, tgt, arr, wav, vis2]).writeto(path)


def score_json(set_dir, est, *extra):
    p = subprocess.run(
        [str(v2ref_bin()), "score", "--sidecar", str(set_dir / "set.json"),
         "--estimates", str(est), "--json", *extra],
        capture_output=True, text=True,
    )
    assert p.returncode in (0, 1), p.stderr
    return p.returncode, json.loads(p.stdout)


@pytest.mark.parametrize("scale", [1.0, 1.3])
def test_an_astropy_written_file_gets_the_csv_verdict(set_dir, scale):
    est = np.genfromtxt(set_dir / "est.csv", delimiter=",", names=True)
    v2 = scale * est["v2_sq"]
    csv = set_dir / f"pipe{scale}.csv"
    np.savetxt(csv, v2, header="v2_sq", comments="", fmt="%.17g")
    path = set_dir / f"pipe{scale}.fits"
    astropy_oifits(path, v2, np.zeros(ROWS, dtype=bool))
    c1, j1 = score_json(set_dir, csv)
    c2, j2 = score_json(set_dir, path, "--estimator", "v2_sq")
    assert c1 == c2 == (0 if scale == 1.0 else 1)
    assert j1["estimators"] == j2["estimators"]


def test_flagged_rows_are_left_out_and_counted(set_dir):
    est = np.genfromtxt(set_dir / "est.csv", delimiter=",", names=True)
    v2 = est["v2_sq"].copy()
    flags = np.zeros(ROWS, dtype=bool)
    flags[[0, 7, 100]] = True
    v2[flags] = np.nan
    path = set_dir / "flagged.fits"
    astropy_oifits(path, v2, flags)
    r = v2ref.read_oifits_estimates(path, sidecar=set_dir / "set.json", estimator="v2_sq")
    assert r["flagged"] == 3 and r["rows"] == ROWS and r["v1_sq"] is None
    np.testing.assert_array_equal(r["v2_sq"], est["v2_sq"][~flags])
    _, j = score_json(set_dir, path, "--estimator", "v2_sq")
    assert j["flagged"] == 3


def test_bad_files_raise_value_errors_naming_the_argument(set_dir, tmp_path):
    bad = tmp_path / "bad.fits"
    bad.write_bytes((set_dir / "est.fits").read_bytes()[:5000])
    with pytest.raises(ValueError, match="path"):
        v2ref.read_oifits(bad)
    wrong = tmp_path / "wave.fits"
    astropy_oifits(wrong, np.full(ROWS, 0.3), np.zeros(ROWS, dtype=bool), eff_wave=1.6e-6)
    with pytest.raises(ValueError, match="EFF_WAVE"):
        v2ref.read_oifits_estimates(wrong, sidecar=set_dir / "set.json", estimator="v2_sq")
    with pytest.raises(ValueError, match="path"):
        v2ref.write_oifits(tmp_path / "x.csv", sidecar=set_dir / "set.json", v2_sq=np.zeros(ROWS))
    with pytest.raises(TypeError, match="path"):
        v2ref.read_oifits(3)
    with pytest.raises(ValueError, match="estimator"):
        v2ref.read_oifits_estimates(wrong, sidecar=set_dir / "set.json", estimator="v3")


def test_python_plan_writes_the_cli_plan_file(set_dir, tmp_path):
    """``plan(oifits=...)`` writes, through the same library code, the file
    ``v2ref plan --oifits`` writes for the same inputs: byte for byte but
    the CHECKSUM and DATASUM cards (cfitsio stamps their comments with
    the time written), and
    it passes the standard's checks."""
    out = tmp_path / "py_plan.fits"
    answer = v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, seeing_arcsec=0.8, oifits=out)
    assert answer["recommended"] is not None

    def cards(b):
        return [b[i : i + 80] for i in range(0, len(b), 80) if not b[i : i + 80].startswith((b"CHECKSUM", b"DATASUM"))]

    assert cards(out.read_bytes()) == cards((set_dir / "plan.fits").read_bytes())
    assert check_oifits2(out) == 1
    with pytest.raises(ValueError, match="^oifits"):
        v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, oifits=tmp_path / "plan.csv")
    assert not (tmp_path / "plan.csv").exists()


def test_score_of_a_flagged_oifits_path(set_dir, tmp_path):
    """``score`` of an OIFITS path reads it as ``v2ref score --estimates``:
    FLAGged rows left out and counted; more than half flagged is the verdict
    "too few rows", not PASS."""
    sidecar = str(set_dir / "set.json")
    est = v2ref.read_oifits_estimates(set_dir / "est.fits", sidecar=sidecar)
    rows = est["rows"]
    v2 = np.array(est["v2_sq"])
    for flagged, too_few in ((3, False), (rows // 2 + 1, True)):
        flag = np.zeros(rows, bool)
        flag[:flagged] = True
        v = v2.copy()
        v[:flagged] = np.nan  # a flagged value need not be a number
        path = tmp_path / f"flag{flagged}.fits"
        v2ref.write_oifits(path, sidecar=sidecar, v2_sq=v)  # NaN rows flagged on write
        got = v2ref.score(path, sidecar)
        assert got["flagged"] == flagged
        assert got["rows"] == rows - flagged
        if too_few:
            assert got["verdict"] == "too few rows" and got["pass"] is False
        else:
            assert "verdict" not in got and got["estimators"][0]["estimator"] == "v2_sq"
    with pytest.raises(ValueError, match="^bins"):
        v2ref.score(set_dir / "est.fits", sidecar, bins="band")


def test_the_keywords_say_where_and_when(set_dir, tmp_path):
    """``target_name``, ``ra_deg``/``dec_deg``, ``date`` and ``site`` (a known
    array, or a name with coordinates) reach the file as the CLI's flags do;
    a bad value raises ValueError naming the keyword, a wrong type TypeError,
    and nothing is written; ``plan`` refuses them without ``oifits``."""
    sidecar = set_dir / "set.json"
    v2 = v2ref.read_oifits(set_dir / "v2.fits")[0]["vis2data"][:, 0]
    out = tmp_path / "where.fits"
    v2ref.write_oifits(out, sidecar=sidecar, v2_sq=v2, target_name="HD 12345", ra_deg=37.95,
                       dec_deg=89.26, date="2026-11-26T03:00:00", site="Mine",
                       site_lon_deg=10, site_lat_deg=45, site_height_m=100.0)
    truth = tmp_path / "truth.fits"
    v2ref.write_oifits_truth(truth, sidecar=sidecar, site="chara", date="2024-02-29")
    plan = tmp_path / "plan.fits"
    v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, oifits=plan, target_name="STAR", site="vlti")
    with fits.open(out) as h:
        assert h[0].header["OBJECT"] == "HD 12345" and h[0].header["DATE-OBS"] == "2026-11-26T03:00:00"
        t = h["OI_TARGET"].data
        assert (t["TARGET"][0], t["RAEP0"][0], t["DECEP0"][0]) == ("HD 12345", 37.95, 89.26)
        a = h["OI_ARRAY"].header
        # astropy's EarthLocation.from_geodetic(10, 45, 100) (WGS84), m.
        assert a["ARRNAME"] == "Mine"
        np.testing.assert_allclose([a["ARRAYX"], a["ARRAYY"], a["ARRAYZ"]],
                                   [4449028.159, 784483.702, 4487419.120], atol=1e-3)
        # 2026-11-26 03:00 UTC is MJD 61370.125; the first row starts there.
        mjd = h["OI_VIS2"].data["MJD"]
        assert 61370.125 < mjd[0] < 61370.125 + 1 / 24
    with fits.open(truth) as h:
        assert h["OI_ARRAY"].header["ARRNAME"] == "CHARA" and h[0].header["DATE-OBS"] == "2024-02-29"
        assert h["OI_TARGET"].data["TARGET"][0] == "V2REF_MODEL"
    with fits.open(plan) as h:
        assert h["OI_ARRAY"].header["ARRNAME"] == "VLTI" and h[0].header["OBJECT"] == "STAR"
    bad = tmp_path / "bad.fits"
    for kw, match in [
        (dict(date="2023-02-29"), "^date: .*YYYY-MM-DD"),
        (dict(ra_deg=360.0, dec_deg=0.0), "^ra_deg: .*0 to 360"),
        (dict(ra_deg=10.0), "^dec_deg"),
        (dict(target_name="x" * 17), "^target_name: .*1 to 16"),
        (dict(site="paranal"), "^site: .*iota, vlti, chara"),
        (dict(site="X", site_lon_deg=1.0, site_lat_deg=1.0, site_height_m=7000.0), "^site_height_m: .*-500 to 6000"),
    ]:
        with pytest.raises(ValueError, match=match):
            v2ref.write_oifits(bad, sidecar=sidecar, v2_sq=v2, **kw)
        assert not bad.exists(), kw
    with pytest.raises(TypeError, match="^ra_deg"):
        v2ref.write_oifits(bad, sidecar=sidecar, v2_sq=v2, ra_deg="10", dec_deg=0.0)
    with pytest.raises(TypeError, match="^site"):
        v2ref.write_oifits_truth(bad, sidecar=sidecar, site=3)
    with pytest.raises(ValueError, match="^target_name: applies when an OIFITS file is written"):
        v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, target_name="STAR")
