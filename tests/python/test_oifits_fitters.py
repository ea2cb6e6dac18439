"""v2ref's OIFITS files in the field's model-fitting packages (the slow
tier: tests/python/requirements-slow.txt installs them, and there a missing
package fails the test rather than skipping it).

- oimodeler's χ² of the true model (the uniform disk the set was
  synthesized from, and the plan's) equals the direct sum
  Σ (VIS2DATA − V²_model)² / VIS2ERR² over the unflagged rows, and its
  model's V² equals the disk's computed here from the file's EFF_WAVE,
  UCOORD and VCOORD: oimodeler reads every row once, weighs it by its
  VIS2ERR and leaves FLAGged rows out.
- PMOIRED loads an estimates file with ``verbose=False`` and ``insname=``
  (its verbose summary takes a numerical gradient over the wavelengths,
  which fails on one channel) and fits the disk's diameter back.

Environment: V2REF_BIN, the v2ref binary (default target/release/v2ref).
"""

import os
from pathlib import Path

import numpy as np
import pytest
from astropy.io import fits

import v2ref

ROOT = Path(__file__).resolve().parents[2]
pytestmark = [pytest.mark.slow, pytest.mark.needs_bin]

ROWS = 200
DIAMETER_MAS = 3.0
#: The plan's source: its default uniform disk (43 mas, at 40 cycles/arcsec).
PLAN_DIAMETER_MAS = 43.0
#: Rows the Python-written file flags (its values NaN: flagged on write).
FLAGGED = (0, 17, 150)
#: oimodeler's χ² against the direct sum over rows of its own model's V²,
#: relative: the same float64 terms summed in another order (1e-15 would
#: do). One row left out, counted twice or weighed by another error moves
#: the sum by about 1/400 of it (more on the truth file, where one row is
#: 1/400 of a sum of equal terms): 1e7 times this.
CHI2_REL = 1e-9
#: oimodeler's V² of the uniform disk against the one computed here (scipy's
#: J1 at the file's EFF_WAVE and baseline): two implementations of one
#: formula, measured 2e-8 apart; a wavelength off by its float32 rounding
#: (6e-8 relative) moves V² by less than 1e-7.
MODEL_ABS = 1e-6
MAS = np.pi / 180 / 3600e3


def v2ref_bin():
    b = Path(os.environ.get("V2REF_BIN", "target/release/v2ref"))
    return b if b.is_absolute() else ROOT / b


def run(*args):
    import subprocess

    p = subprocess.run([str(v2ref_bin()), *map(str, args)], capture_output=True, text=True)
    assert p.returncode == 0, (args, p.stderr)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """{file: the uniform disk's diameter, mas}: a UD set's truth and
    estimates (CLI), the estimates with rows flagged (Python), a plan's."""
    d = tmp_path_factory.mktemp("fitters")
    run("synth", "--out", d / "ud", "--rows", ROWS, "--samples", 64, "--source", "ud",
        "--diameter-mas", DIAMETER_MAS, "--baseline-m", 60, "--reference-blocks", 8,
        "--quiet", "--oifits")
    run("estimate", "--sidecar", d / "ud.json", "--out", d / "est.fits")
    est = v2ref.read_oifits(d / "est.fits")
    v2 = est[1]["vis2data"][:, 0].copy()
    v2[list(FLAGGED)] = np.nan
    v2ref.write_oifits(d / "flagged.fits", sidecar=d / "ud.json", v2_sq=v2)
    run("plan", "--quiet", "--fringe-hz", 300, "--stroke-um", 32, "--scans", 64, "--seeing-arcsec", 0.8,
        "--diameter-mas", PLAN_DIAMETER_MAS, "--oifits", d / "plan.fits")
    assert (d / "plan.fits").exists(), "no setting of the plan reaches its target"
    return {
        d / "ud.truth.fits": DIAMETER_MAS,
        d / "est.fits": DIAMETER_MAS,
        d / "flagged.fits": DIAMETER_MAS,
        d / "plan.fits": PLAN_DIAMETER_MAS,
    }


def vis2_tables(path):
    """Every OI_VIS2 table of the file in order: (VIS2DATA, VIS2ERR, FLAG,
    the uniform disk's V² at its EFF_WAVE and baseline) as flat arrays, with
    the disk's diameter still to give: a function of it."""
    with fits.open(path) as h:
        waves = {x.header["INSNAME"]: x.data["EFF_WAVE"] for x in h if x.name == "OI_WAVELENGTH"}
        out = []
        for x in h:
            if x.name != "OI_VIS2":
                continue
            wave = np.float64(waves[x.header["INSNAME"]][0])
            b = np.hypot(x.data["UCOORD"], x.data["VCOORD"])
            out.append((np.ravel(x.data["VIS2DATA"]), np.ravel(x.data["VIS2ERR"]),
                        np.ravel(x.data["FLAG"]), b / wave))
    return out


def ud_v2(freq_per_rad, diameter_mas):
    """V² of a uniform disk: (2 J1(x)/x)², x = π θ B/λ."""
    # Imported here: scipy comes with the slow tier's packages
    # (requirements-slow.txt), and the default tier collects this module.
    from scipy.special import j1

    x = np.pi * diameter_mas * MAS * freq_per_rad
    return (2 * j1(x) / x) ** 2


def oimodeler_model_v2(sim):
    """oimodeler's V² of the model, per OI_VIS2 table in file order."""
    return [np.ravel(h.data["VIS2DATA"]) for hl in sim.simulatedData.data for h in hl if h.name == "OI_VIS2"]


def test_oimodeler_chi2_of_the_true_model_is_the_direct_sum(files):
    import oimodeler as oim

    for path, diameter in files.items():
        data = oim.oimData(str(path))
        data.prepareData()
        sim = oim.oimSimulator(data=data, model=oim.oimModel(oim.oimUD(d=diameter)))
        sim.compute(computeChi2=True, computeSimulatedData=True)
        tables = vis2_tables(path)
        models = oimodeler_model_v2(sim)
        assert len(models) == len(tables), path.name
        chi2, rows = 0.0, 0
        for (v2, err, flag, freq), model in zip(tables, models):
            np.testing.assert_allclose(model, ud_v2(freq, diameter), rtol=0, atol=MODEL_ABS,
                                       err_msg=path.name)
            keep = ~flag
            chi2 += float(np.sum(((v2 - model) / err)[keep] ** 2))
            rows += int(keep.sum())
        if path.name == "flagged.fits":
            assert rows == ROWS - len(FLAGGED)
        assert sim.nelChi2 == rows, (path.name, sim.nelChi2, rows)
        assert sim.chi2 == pytest.approx(chi2, rel=CHI2_REL), path.name


def test_pmoired_loads_and_fits_an_estimates_file(files):
    import pmoired

    path = next(p for p in files if p.name == "est.fits")
    oi = pmoired.OI(str(path), verbose=False, insname="V2REF_V2SQ")
    assert len(oi.data) == 1 and oi.data[0]["insname"] == "V2REF_V2SQ"
    oi.setupFit({"obs": ["V2"]})
    oi.doFit({"ud": 2.0})
    best, sigma = oi.bestfit["best"]["ud"], oi.bestfit["uncer"]["ud"]
    # The diameter back within 5 of its own standard errors (0.28 mas on
    # 200 rows), and a reduced χ² near one: VIS2ERR is the rows' scatter
    # (the reduced χ² of 200 rows has a standard deviation of 0.1; the
    # seed is fixed; a VIS2ERR off by a factor 1.25 either way would give
    # 0.6 or 1.5).
    assert 0 < sigma < 0.5, sigma
    assert abs(best - DIAMETER_MAS) < 5 * sigma, (best, sigma)
    assert 0.7 < oi.bestfit["chi2"] < 1.3, oi.bestfit["chi2"]
