"""``v2ref.plan`` takes every flag of ``v2ref plan``: the flags are read
from the binary's ``--help`` (not from a list kept here), so a flag added
to the command line without its keyword fails this test. The magnitude
keywords give the CLI's photon rate, and half of them is refused by name."""

import json
import re
import subprocess

import pytest

import v2ref
from conftest import release_binary

# The terminal's own flags: the table instead of JSON, progress, rows
# shown, the figure drawn from the answer, overwriting an output. Python
# returns the answer itself.
CLI_ONLY = {"json", "quiet", "all", "svg", "force", "help"}
# The target list is its own function (v2ref.plan_targets), which returns
# the table rather than writing it (--out).
CLI_ONLY |= {"targets", "out"}
# Every flag of `plan` has its keyword (`instrument` included: plan()
# records the keywords given, so that its preset fills only the others).
NOT_YET = set()


def _cli_flags():
    out = subprocess.run(
        [str(release_binary()), "plan", "--help"], capture_output=True, text=True, check=True
    ).stdout
    flags = {m.replace("-", "_") for m in re.findall(r"^\s+(?:-\w, )?--([a-z0-9-]+)", out, re.M)}
    # --no-photon-noise is the keyword photon_noise=False.
    return {f[3:] if f == "no_photon_noise" else f for f in flags}


@pytest.mark.needs_bin
def test_python_plan_takes_every_cli_flag():
    import inspect

    keywords = set(inspect.signature(v2ref.plan).parameters)
    flags = _cli_flags()
    assert {"magnitude", "magnitude_band", "throughput", "frame_rate_hz"} <= flags
    missing = sorted(flags - CLI_ONLY - NOT_YET - keywords)
    assert not missing, f"v2ref plan flags without a v2ref.plan keyword: {missing}"


@pytest.mark.needs_bin
def test_magnitude_gives_the_clis_photon_rate():
    import json

    common = dict(wavelength_um=1.65, bandwidth_nm=300.0, aperture_m=1.8)
    args = ["--wavelength-um", "1.65", "--bandwidth-nm", "300", "--aperture-m", "1.8"]
    grid = dict(fringe_hz=[500.0], stroke_um=[16.0], scans=32, time_budget_s=1.0)
    args += ["--fringe-hz", "500", "--stroke-um", "16", "--scans", "32", "--time-budget-s", "1"]
    mag = ["--magnitude", "5", "--magnitude-band", "h", "--throughput", "0.02"]
    out = subprocess.run(
        [str(release_binary()), "plan", *args, *mag, "--json", "--quiet"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    cli = json.loads(out)
    py = v2ref.plan(magnitude=5.0, magnitude_band="h", throughput=0.02, **common, **grid)
    assert py["inputs"]["photon_rate_per_s"] == cli["inputs"]["photon_rate_per_s"]
    assert py["photometry"]["magnitude"] == 5.0


@pytest.mark.parametrize(
    "kw, name",
    [
        (dict(magnitude=5.0), "magnitude_band"),
        (dict(magnitude_band="h", throughput=0.1), "magnitude_band"),
        (dict(magnitude=5.0, magnitude_band="h", throughput=0.1, photon_rate_per_s=1e6), "photon_rate_per_s"),
        (dict(magnitude=5.0, magnitude_band="q", throughput=0.1), "magnitude_band"),
        (dict(frame_rate_hz=-1.0), "frame_rate_hz"),
    ],
)
def test_bad_plan_keywords_are_refused_by_name(kw, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        v2ref.plan(fringe_hz=[500.0], stroke_um=[16.0], scans=32, time_budget_s=1.0, **kw)


@pytest.mark.needs_bin
def test_a_preset_with_one_keyword_given_is_the_clis_plan():
    """``instrument=`` fills what was not given, as ``--instrument`` does:
    a preset with its read noise overridden gives the CLI's plan, number for
    number; and a keyword given at its default value is kept (the preset's
    band would move the plan's band otherwise)."""
    grid = dict(fringe_hz=[50.0, 200.0], stroke_um=[32.0], scans=64)
    flags = ["--fringe-hz", "50", "--fringe-hz", "200", "--stroke-um", "32", "--scans", "64"]
    cli = subprocess.run(
        [str(release_binary()), "plan", "--quiet", "--json", "--instrument", "vlti-pionier",
         "--read-noise", "2.5", *flags],
        capture_output=True, text=True, check=True,
    ).stdout
    py = v2ref.plan(instrument="vlti-pionier", read_noise=2.5, **grid)
    assert py == json.loads(cli)
    assert py["inputs"]["instrument"]["read_noise"] == 2.5
    assert py["inputs"]["instrument"]["spectrum"]["wavelength_um"] == 1.65
    kept = v2ref.plan(instrument="vlti-pionier", wavelength_um=2.2, **grid)
    assert kept["inputs"]["instrument"]["spectrum"]["wavelength_um"] == 2.2
    assert kept["inputs"]["instrument"]["read_noise"] == 1.0
