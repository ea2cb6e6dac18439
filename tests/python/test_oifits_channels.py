"""OIFITS of six spectral channels (issue 54), both ways with astropy.

A file astropy writes as a pipeline would (EFF_WAVE in decreasing order as
float32, FLAG per channel, TDIM) is read through v2ref's Rust reader
(``v2ref.read_oifits``): wavelengths, values and flags per (row, channel)
as written, bit for bit. The file v2ref's writer makes for six channels
(``tests/data/oifits_channels6.fits``; ``tests/oifits_channels_files.rs`` checks
it is what the writer writes today) is read by astropy: NWAVE = 6 in every
column, one OI_WAVELENGTH row per channel in decreasing wavelength, the
values of the formula it was written from, VIS2ERR one per channel.
"""

from pathlib import Path

import numpy as np
from astropy.io import fits

import v2ref

ROOT = Path(__file__).resolve().parents[2]
FIXTURE = ROOT / "tests" / "data" / "oifits_channels6.fits"
ROWS, NWAVE = 8, 6


def pipeline_file(path, eff_wave, vis2data, flag):
    """An OIFITS v2 file as a pipeline writes it: no v2ref keyword."""
    rows, nwave = vis2data.shape
    prim = fits.PrimaryHDU()
    prim.header["CONTENT"] = "OIFITS2"
    tgt = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=[1]), fits.Column("TARGET", "16A", array=["HD 1"]),
    ], name="OI_TARGET")
    wav = fits.BinTableHDU.from_columns([
        fits.Column("EFF_WAVE", "E", unit="m", array=eff_wave),
        fits.Column("EFF_BAND", "E", unit="m", array=np.full(nwave, 5e-8, dtype=np.float32)),
    ], name="OI_WAVELENGTH")
    vis2 = fits.BinTableHDU.from_columns([
        fits.Column("TARGET_ID", "I", array=np.ones(rows)),
        fits.Column("MJD", "D", array=60000 + np.arange(rows) / 1440),
        fits.Column("VIS2DATA", f"{nwave}D", dim=f"({nwave})", array=vis2data),
        fits.Column("VIS2ERR", f"{nwave}D", dim=f"({nwave})", array=np.full((rows, nwave), 0.05)),
        fits.Column("FLAG", f"{nwave}L", dim=f"({nwave})", array=flag),
    ], name="OI_VIS2")
    for h in (wav, vis2):
        h.header["OI_REVN"] = 2
        h.header["INSNAME"] = "SPEC6"
    fits.HDUList([prim, tgt, wav, vis2]).writeto(path, checksum=True)


def test_a_pipelines_six_channels_in_decreasing_float32_wavelength_are_read_as_written(tmp_path):
    eff_wave = np.linspace(2.35e-6, 2.05e-6, NWAVE).astype(np.float32)
    rng = np.random.default_rng(54)
    vis2data = rng.uniform(0.2, 0.9, (ROWS, NWAVE))
    flag = np.zeros((ROWS, NWAVE), dtype=bool)
    flag[1, 2] = flag[5, 0] = flag[5, 5] = True
    path = tmp_path / "spec6.fits"
    pipeline_file(path, eff_wave, vis2data, flag)
    (t,) = v2ref.read_oifits(path)
    assert t["insname"] == "SPEC6" and t["estimator"] is None
    # float32 wavelengths widened exactly, in the file's (decreasing) order.
    assert t["eff_wave_m"].tolist() == eff_wave.astype(np.float64).tolist()
    assert np.all(np.diff(t["eff_wave_m"]) < 0)
    assert t["vis2data"].shape == (ROWS, NWAVE)
    assert t["vis2data"].tobytes() == vis2data.tobytes()
    assert t["flag"].tolist() == flag.tolist()


def test_v2refs_six_channel_file_reads_in_astropy_as_its_formula():
    with fits.open(FIXTURE, checksum=True) as hdul:
        prim = hdul[0].header
        assert prim["INSMODE"] == "DISPERSED"
        waves = [h for h in hdul if h.name == "OI_WAVELENGTH"]
        tables = [h for h in hdul if h.name == "OI_VIS2"]
        assert [h.header["INSNAME"] for h in tables] == ["V2REF_V1SQ", "V2REF_V2SQ"]
        for w, t in zip(waves, tables):
            eff = w.data["EFF_WAVE"]
            assert eff.dtype == np.dtype(">f4") and eff.shape == (NWAVE,)
            # The set's channels in increasing wavenumber: decreasing wavelength in K.
            assert np.all(np.diff(eff) < 0) and 2.0e-6 < eff[-1] and eff[0] < 2.4e-6
            assert np.all(w.data["EFF_BAND"] > 0)
            assert t.header["TDIM5"] == f"({NWAVE})" and t.header["TFORM5"] == f"{NWAVE}D"
            data, err, flag = t.data["VIS2DATA"], t.data["VIS2ERR"], t.data["FLAG"]
            assert data.shape == err.shape == flag.shape == (ROWS, NWAVE)
            e = 0.0 if t.header["V2R_EST"] == "V1SQ" else 1.0
            r = np.arange(ROWS)[:, None] + 1
            j = np.arange(NWAVE)[None, :] + 1
            assert np.array_equal(data, 0.5 * e + 0.1 * r + 0.01 * j)
            # One closed-form error per channel, the same on every row.
            assert np.all(err > 0) and np.all(err == err[0])
            flagged = np.argwhere(flag).tolist()
            assert flagged == ([[2, 4]] if e else [])
    # And v2ref's own reader agrees with astropy on every value.
    ours = v2ref.read_oifits(FIXTURE)
    with fits.open(FIXTURE) as hdul:
        for t, h in zip(ours, [h for h in hdul if h.name == "OI_VIS2"]):
            assert t["vis2data"].tobytes() == np.asarray(h.data["VIS2DATA"], dtype=float).tobytes()
            assert t["flag"].tolist() == h.data["FLAG"].tolist()
