"""Spectral channels from Python (issue 54): ``channels=``, ``resolution=``
and ``channels_csv=`` on the functions that take the band. ``bias``,
``snr`` and ``simulate`` return the CLI's JSON per channel; bad values
are a TypeError or ValueError naming the keyword; the functions that do
not take channels yet refuse them (synthesize, estimate and score take
them: test_channels_kit.py).
"""

import json
import os
import subprocess

import numpy as np
import pytest

import v2ref
from conftest import release_binary

TABLE = "wavelength_lo_um,wavelength_hi_um,response\n2.0,2.2,1\n2.2,2.4,3\n"


def _cli(*args):
    done = subprocess.run([str(release_binary()), *args, "--json"], capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


@pytest.mark.needs_bin
def test_bias_and_snr_per_channel_are_the_clis():
    """The dict is the CLI's JSON, channels and combination included."""
    b = v2ref.bias(channels=4, dispersion_pp_rad=2.0, integrating=True)
    assert b == _cli("bias", "--channels", "4", "--dispersion-pp-rad", "2", "--integrating")
    assert [c["channel"] for c in b["channels"]] == [1, 2, 3, 4]
    s = v2ref.snr(resolution=20.0, read_noise=1.0)
    assert s == _cli("snr", "--resolution", "20", "--read-noise", "1")
    q = np.array([c["photon_share"] for c in s["channels"]])
    sigma = np.array([c["v1_sq"]["sigma"] for c in s["channels"]])
    # The stated combination: photon-weighted, σ of independent channels.
    assert s["combined"]["v1_sq"]["sigma"] == pytest.approx(np.sqrt(np.sum((q * sigma) ** 2)), rel=1e-12)  # tol: summation order
    assert "piston" in s["combined"]["note"]


def test_one_channel_is_the_wide_band():
    """``channels=1``: the wide band's numbers, and its own line the same."""
    wide = v2ref.bias()
    one = v2ref.bias(channels=1)
    line = one.pop("channels")[0]
    assert one == wide
    assert line["photon_share"] == 1.0
    for k in ("v1", "v2", "v_mono"):
        assert line["wide_band"][k] == wide[k]


def test_a_channel_table_file(tmp_path):
    """A table's responses set the photon shares; a FIFO is refused at once."""
    path = tmp_path / "two.csv"
    path.write_text(TABLE)
    b = v2ref.bias(channels_csv=path)
    shares = [c["photon_share"] for c in b["channels"]]
    # Flat band: each channel's light is its width in wavenumber times its response.
    light = np.array([3 * (1 / 2.2 - 1 / 2.4), 1 / 2.0 - 1 / 2.2])
    assert shares == pytest.approx(list(light / light.sum()), rel=1e-14)  # tol: a few roundings
    fifo = tmp_path / "fifo.csv"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match="channels_csv"):
        v2ref.bias(channels_csv=fifo)
    bad = tmp_path / "overlap.csv"
    bad.write_text("wavelength_lo_um,wavelength_hi_um,response\n2.0,2.25,1\n2.2,2.4,1\n")
    with pytest.raises(ValueError, match="^channels_csv: .*overlap"):
        v2ref.snr(channels_csv=bad)


def test_bad_values_name_the_keyword():
    with pytest.raises(TypeError, match="^channels: "):
        v2ref.bias(channels=True)
    with pytest.raises(TypeError, match="^channels: "):
        v2ref.bias(channels=2.5)
    with pytest.raises(ValueError, match="^channels: .*4096"):
        v2ref.bias(channels=0)
    with pytest.raises(ValueError, match="^resolution: "):
        v2ref.snr(resolution=-1.0)
    with pytest.raises(ValueError, match="^resolution: .*DFT bin"):
        v2ref.bias(resolution=100.0)
    with pytest.raises(ValueError, match="^channels: .*resolution"):
        v2ref.bias(channels=2, resolution=20.0)
    with pytest.raises(TypeError, match="^channels_csv: "):
        v2ref.bias(channels_csv=3)


def test_functions_without_channels_refuse_them(tmp_path):
    with pytest.raises(ValueError, match="^channels: not taken by `plan`"):
        v2ref.plan(channels=2)
    with pytest.raises(ValueError, match="^resolution: not taken by `piston`"):
        v2ref.piston(resolution=20.0, scans=2)
    with pytest.raises(ValueError, match="^channels: not taken by `synthesize with client or checkpoint`"):
        v2ref.synthesize(channels=2, rows=8, checkpoint=tmp_path / "ck")
    with pytest.raises(ValueError, match="^channels: not taken by `simulate with client or checkpoint`"):
        v2ref.simulate(channels=2, trials=8, checkpoint=tmp_path / "ck")


def test_simulate_per_channel_has_the_correlation_and_both_sigmas():
    r = v2ref.simulate(channels=3, trials=2000, seed=3, photons=100.0)
    assert len(r["channels"]) == 3
    for name in ("combined_v1_sq", "combined_v2_sq"):
        c = r[name]
        rho = np.array(c["correlation"])
        assert rho.shape == (3, 3)
        assert np.allclose(np.diag(rho), 1.0, rtol=0, atol=1e-12)  # tol: x/x rounding
        assert c["sigma"] == pytest.approx(np.sqrt(c["variance"]), rel=1e-15)  # tol: one sqrt
        assert c["independent_sigma"] > 0
    with pytest.raises(ValueError, match="^formula: "):
        v2ref.simulate(channels=3, trials=8, formula="published")
