"""The independent NumPy pipeline (examples/python/numpy_pipeline.py) scored
by `v2ref score` on every conformance vector in golden/vectors/.

- the correct pipeline (bins positive, bias model) must pass (exit 0) on
  every vector;
- its deliberate mistakes must fail (exit 1) wherever they change the
  answer: `photon-bias-from-m` on the vectors with photon noise (on the
  others it must give the same estimates and pass), `no-calibration` on all;
- the `counts` bias convention must pass on the noise-only vectors
  (noise_*).

Environment:
    V2REF_BIN             the v2ref binary (default target/release/v2ref,
                          relative to the repository root)
    V2REF_VECTORS         folder of the vectors (default golden/vectors)
    V2REF_SCORE_SUMMARY   if set, a Markdown table of the z-scores
                          (vector × variant) is written there
"""

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PIPELINE = ROOT / "examples" / "python" / "numpy_pipeline.py"
VECTORS = Path(os.environ.get("V2REF_VECTORS", ROOT / "golden" / "vectors"))
if not VECTORS.is_absolute():
    VECTORS = ROOT / VECTORS

# The catalogue of crates/v2ref-core/src/conformance/vectors.rs.
CATALOGUE = [
    "noise_gaussian",
    "noise_poisson",
    "noise_both",
    "bandwidth_disk",
    "dispersion",
    "short_scan_odd",
    "integrating",
    "piston_low",
    "piston_high",
]

# (name, pipeline flags, score flags)
VARIANTS = {
    "correct": (["--bins", "positive", "--bias", "model"], ["--bins", "positive", "--bias", "model"]),
    "photon-bias-from-m": (
        ["--bins", "positive", "--bias", "model", "--mistake", "photon-bias-from-m"],
        ["--bins", "positive", "--bias", "model"],
    ),
    "no-calibration": (
        ["--bins", "positive", "--bias", "model", "--mistake", "no-calibration"],
        ["--bins", "positive", "--bias", "model"],
    ),
    "counts": (["--bins", "positive", "--bias", "counts"], ["--bins", "positive", "--bias", "counts"]),
}

# (vector, variant, expected exit, exit, {estimator: (z_mean, z_var)})
RESULTS = []


def v2ref_bin():
    b = Path(os.environ.get("V2REF_BIN", "target/release/v2ref"))
    return b if b.is_absolute() else ROOT / b


def vector_names():
    if not VECTORS.is_dir():
        return []
    return sorted(p.stem for p in VECTORS.glob("*.json"))


def sidecar(name):
    with open(VECTORS / f"{name}.json", encoding="utf-8") as f:
        return json.load(f)


def test_vectors_present():
    """The vectors must be there: a missing folder fails, never skips."""
    assert VECTORS.is_dir(), f"no conformance vectors: {VECTORS} is missing"
    names = vector_names()
    assert names, f"no conformance vectors: no *.json in {VECTORS}"
    missing = [n for n in CATALOGUE if n not in names]
    assert not missing, f"vectors of the catalogue missing from {VECTORS}: {missing}"
    for n in names:
        sc = sidecar(n)
        assert sc.get("format") == "v2ref-synth-1", f"{n}.json: format {sc.get('format')!r}"
        assert (VECTORS / sc["data"]["npy"]).is_file(), f"{n}.json: {sc['data']['npy']} missing"


def run_pipeline(name, flags, out):
    r = subprocess.run(
        [sys.executable, str(PIPELINE), str(VECTORS / f"{name}.json"), "--out", str(out), *flags],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, f"pipeline {flags} on {name} failed:\n{r.stderr}"


def score(name, estimates, flags):
    """(exit status, parsed --json report or None, stderr)."""
    r = subprocess.run(
        [
            str(v2ref_bin()),
            "score",
            "--sidecar",
            str(VECTORS / f"{name}.json"),
            "--estimates",
            str(estimates),
            "--json",
            *flags,
        ],
        capture_output=True,
        text=True,
    )
    report = None
    if r.stdout.strip():
        try:
            report = json.loads(r.stdout)
        except json.JSONDecodeError:
            pass
    return r.returncode, report, r.stderr + r.stdout


def z_scores(report):
    """{estimator: (z_mean, z_var)} from score's --json report."""
    out = {}
    if not report:
        return out
    ests = report.get("estimators", [])
    if isinstance(ests, dict):
        ests = [dict(v, estimator=k) for k, v in ests.items()]
    for e in ests:
        out[e.get("estimator")] = (e.get("z_mean"), e.get("z_var"))
    return out


def read_estimates(path):
    with open(path, newline="", encoding="utf-8") as f:
        return [(r["v1_sq"], r["v2_sq"]) for r in csv.DictReader(f)]


def cases():
    """(vector, variant, expected exit) for every vector present."""
    out = []
    for name in vector_names():
        photon = bool(sidecar(name)["inputs"]["photon_noise"])
        out.append((name, "correct", 0))
        # Without photon noise the mistake changes nothing: same answer, pass.
        out.append((name, "photon-bias-from-m", 1 if photon else 0))
        out.append((name, "no-calibration", 1))
        if name.startswith("noise_"):
            out.append((name, "counts", 0))
    return out


@pytest.mark.needs_bin
@pytest.mark.parametrize("name,variant,expected", cases(), ids=lambda v: str(v))
def test_score(name, variant, expected, tmp_path):
    pipe_flags, score_flags = VARIANTS[variant]
    est = tmp_path / f"{name}.{variant}.csv"
    run_pipeline(name, pipe_flags, est)
    if variant == "photon-bias-from-m" and expected == 0:
        correct = tmp_path / f"{name}.correct.csv"
        run_pipeline(name, VARIANTS["correct"][0], correct)
        assert read_estimates(est) == read_estimates(correct), (
            f"{name} has no photon noise: the mistake should change nothing"
        )
    code, report, text = score(name, est, score_flags)
    RESULTS.append((name, variant, expected, code, z_scores(report)))
    assert code in (0, 1), f"score refused the estimates of {variant} on {name} (exit {code}):\n{text}"
    assert report is not None, f"score --json printed no JSON:\n{text}"
    assert code == expected, (
        f"{variant} on {name}: score exited {code}, expected {expected}\n"
        + json.dumps(report, indent=1)
    )


def _fmt(z):
    return "" if z is None else f"{z:.3f}"


@pytest.fixture(scope="session", autouse=True)
def write_summary():
    yield
    path = os.environ.get("V2REF_SCORE_SUMMARY")
    if not path:
        return
    lines = [
        "| vector | variant | expected | exit | V1² z_mean | V1² z_var | V2² z_mean | V2² z_var |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, variant, expected, code, z in RESULTS:
        v1 = z.get("v1_sq", (None, None))
        v2 = z.get("v2_sq", (None, None))
        lines.append(
            f"| {name} | {variant} | {expected} | {code} | "
            f"{_fmt(v1[0])} | {_fmt(v1[1])} | {_fmt(v2[0])} | {_fmt(v2[1])} |"
        )
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")


def _load_pipeline():
    import importlib.util

    spec = importlib.util.spec_from_file_location("numpy_pipeline", PIPELINE)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.parametrize("n", [8, 7, 25])
@pytest.mark.parametrize("bias", ["model", "counts"])
@pytest.mark.parametrize("subtracted", [True, False])
def test_pipeline_against_definitions(n, bias, subtracted):
    """The FFT pipeline against the definitions summed term by term (no
    vectors needed): naive DFT, b1 = |K|Σv_i, b2 = Σ_i |u_i|² v_i."""
    import cmath

    import numpy as np

    p = _load_pipeline()
    rng = np.random.default_rng(n)
    cont = rng.uniform(5, 10, n)
    mean = cont + rng.uniform(-3, 3, n)
    band = [1, 2] if n > 4 else [1]
    sc = {
        "inputs": {"read_noise": 1.5, "photon_noise": True},
        "continuum_subtracted": subtracted,
        "continuum_photons": cont.tolist(),
        "mean_counts_photons": mean.tolist(),
        "truth": {
            "windows": [
                {"bins": w, "bin_indices": b, "calibration": {"v1_sq": 3.0, "v2_sq": 7.0}}
                for w, b in (
                    ("positive", list(range(1, (n + 1) // 2))),
                    ("band", band),
                    ("all", list(range(n))),
                )
            ]
        },
    }
    rows = rng.normal(0, 4, (3, n)) + (0 if subtracted else cont)
    for window, bins in (
        ("positive", list(range(1, (n + 1) // 2))),
        ("band", band),
        ("all", list(range(n))),
    ):
        v1, v2 = p.estimate(sc, rows, window, bias, model="sidecar")
        for r in range(rows.shape[0]):
            m = [rows[r, i] - (0 if subtracted else cont[i]) for i in range(n)]
            dft = [sum(m[i] * cmath.exp(-2j * cmath.pi * i * k / n) for i in range(n)) for k in bins]
            raw1 = sum(abs(b) ** 2 for b in dft)
            raw2 = abs(sum(dft)) ** 2
            nn = [mean[i] if bias == "model" else cont[i] + m[i] for i in range(n)]
            v = [1.5**2 + nn[i] for i in range(n)]
            u2 = [abs(sum(cmath.exp(-2j * cmath.pi * i * k / n) for k in bins)) ** 2 for i in range(n)]
            b1 = len(bins) * sum(v)
            b2 = sum(u2[i] * v[i] for i in range(n))
            assert v1[r] == pytest.approx((raw1 - b1) / 3.0, rel=1e-10, abs=1e-9)
            assert v2[r] == pytest.approx((raw2 - b2) / 7.0, rel=1e-10, abs=1e-9)


# The pipeline's model (continuum, mean counts, bins, calibration), computed
# from the stated inputs, against v2ref's in the sidecar: two quadratures of
# the same integral (v2ref's composite Gauss–Legendre panels, the
# pipeline's 256 nodes over the band, J1 by its integral against v2ref's
# recurrence), each at rounding; measured worst 2e-15 relative, 1e-12 leaves
# room for other platforms' libm.
MODEL_REL = 1e-12


@pytest.mark.parametrize("name", CATALOGUE)
def test_model_from_inputs_equals_the_sidecars(name):
    import numpy as np

    p = _load_pipeline()
    sc = sidecar(name)
    for window in ("positive", "band", "all"):
        c, n, bins, cal = p.model_from_inputs(sc["inputs"], window)
        c2, n2, bins2, cal2 = p.model_from_sidecar(sc, window)
        assert list(bins) == list(bins2), (name, window)
        np.testing.assert_allclose(c, c2, rtol=MODEL_REL, atol=0)
        np.testing.assert_allclose(n, n2, rtol=MODEL_REL, atol=0)
        np.testing.assert_allclose(cal, cal2, rtol=MODEL_REL, atol=0)


# The planted fringe-model error: the band stated 20 % wider than the one
# the data were synthesized with (a synthesizer whose bandwidth smearing is
# not the stated band's). Truth and calibration in the sidecar are the
# synthesizer's, so they agree with its data. Measured on bandwidth_disk:
# the independent model's mean V1² moves by 15.5 standard errors (5 % wider:
# 3.0, within the score's threshold).
PLANTED_BANDWIDTH_FACTOR = 1.2


@pytest.mark.needs_bin
def test_a_fringe_model_error_is_caught_by_the_independent_model(tmp_path):
    """A pipeline reading the model from the sidecar cannot see an error of
    the synthesizer's fringe model (it cancels between the data and the
    calibration): it passes. The same pipeline computing its model from
    the stated inputs fails the score."""
    import shutil

    name = "bandwidth_disk"
    sc = sidecar(name)
    sc["inputs"]["spectrum"]["bandwidth_nm"] *= PLANTED_BANDWIDTH_FACTOR
    shutil.copy(VECTORS / sc["data"]["npy"], tmp_path / sc["data"]["npy"])
    planted = tmp_path / f"{name}.json"
    planted.write_text(json.dumps(sc), encoding="utf-8")

    def exit_status(model):
        est = tmp_path / f"{model}.csv"
        r = subprocess.run(
            [sys.executable, str(PIPELINE), str(planted), "--out", str(est), "--model", model],
            capture_output=True,
            text=True,
        )
        assert r.returncode == 0, r.stderr
        s = subprocess.run(
            [str(v2ref_bin()), "score", "--sidecar", str(planted), "--estimates", str(est)],
            capture_output=True,
            text=True,
        )
        assert s.returncode in (0, 1), s.stderr
        return s.returncode

    assert exit_status("sidecar") == 0
    assert exit_status("inputs") == 1
