"""Issue 53: no type guessed. Every numeric keyword of every public
function takes a number (the grids ``plan(fringe_hz=, stroke_um=)`` and
``piston(fringe_hz=)`` also a sequence of numbers) and refuses anything
else, a string above all, by name; a bool is no number and no count. The
numeric keywords are read from the signatures (an annotation naming float
or int), so a keyword added later is tried too. The target list's errors
that Python reaches through ``plan_targets`` are the CLI's."""

import inspect
import re
import typing

import numpy as np
import pytest

import v2ref

# What each function needs besides the keyword tried, so that the check
# of that keyword is what refuses the call (none of these runs anything);
# "{tmp}" is the test's folder.
NEEDS = {
    "estimate": dict(interferograms=np.ones((4, 128))),
    "score": dict(estimates={"v1_sq": np.zeros(4)}, sidecar={}),
    "score_oifits": dict(path="{tmp}/e.fits", sidecar={}),
    "write_oifits": dict(path="{tmp}/w.fits", sidecar={}),
    "write_oifits_truth": dict(path="{tmp}/t.fits", sidecar={}),
    "photon_rate": dict(magnitude=5.0, band="H", throughput=0.1),
}


def _needs(function, tmp):
    return {k: v.format(tmp=tmp) if isinstance(v, str) else v for k, v in NEEDS.get(function, {}).items()}


def _numeric(annotation) -> bool:
    """An annotation naming float or int (not only bool or str)."""
    return re.search(r"\b(float|int)\b", repr(annotation)) is not None


def _numeric_keywords():
    """(function name, keyword) of every public function's numeric keywords."""
    out = []
    for name in v2ref.__all__:
        f = getattr(v2ref, name)
        if not callable(f):
            continue
        hints = typing.get_type_hints(f)
        for k in inspect.signature(f).parameters:
            if k in hints and _numeric(hints[k]) and k not in NEEDS.get(name, {}):
                out.append((name, k))
    return out


CASES = _numeric_keywords()


def test_the_table_holds_every_numeric_keyword():
    """The table's power: the keywords this issue names are in it."""
    for case in [
        ("plan", "fringe_hz"), ("plan", "stroke_um"), ("piston", "fringe_hz"),
        ("simulate", "chunk_units"), ("score", "alpha"), ("write_oifits", "ra_deg"),
        ("synthesize", "rows"), ("estimate", "photons"), ("photon_rate", "aperture_m"),
    ]:
        assert case in CASES, case
    assert len({name for name, _ in CASES}) >= 10


# Values no numeric keyword may take: each a type guessed on main (a
# string iterated, a bool counted as 1, a list or a dict taken as numbers).
REFUSED = ["35", b"35", "1:10:2", True, np.bool_(False), {"a": 1}, {1.0, 2.0}, 1j]


@pytest.mark.parametrize("function, keyword", CASES)
def test_each_numeric_keyword_refuses_what_is_no_number_by_name(function, keyword, tmp_path):
    f = getattr(v2ref, function)
    needs = _needs(function, tmp_path)
    for value in REFUSED:
        with pytest.raises((TypeError, ValueError)) as raised:
            f(**needs, **{keyword: value})
        message = str(raised.value)
        assert message.startswith((f"{keyword}:", f"{keyword}[")), (function, keyword, value, message)
        assert "accepted" in message, (function, keyword, value, message)


GRIDS = [("plan", "fringe_hz"), ("plan", "stroke_um"), ("piston", "fringe_hz")]


@pytest.mark.parametrize("function, keyword", GRIDS)
def test_a_grid_keyword_refuses_a_string_and_a_bad_element_by_name(function, keyword):
    f = getattr(v2ref, function)
    for value in ["35", "99", "1:10:2", "20:2000:20:log"]:
        with pytest.raises(TypeError, match=rf"^{keyword}: '.*' is not a number or a sequence of numbers; accepted: .*numpy.linspace"):
            f(**{keyword: value})
    for value, at in [([300.0, "5"], 1), ((True, 3.0), 0), (np.array(["3", "5"]), 0), ([None], 0)]:
        with pytest.raises(TypeError, match=rf"^{keyword}\[{at}\]: .* is not a real number"):
            f(**{keyword: value})
    with pytest.raises(TypeError, match=rf"^{keyword}: "):
        f(**{keyword: np.ones((2, 2))})


# One grid point, a short Monte Carlo: each plan well under a second.
SMALL_PLAN = dict(scans=50, wavelength_um=1.65, bandwidth_nm=300.0, aperture_m=1.8, target_sigma_v2=1e-2)


def _grid_of(answer):
    return sorted({(p["fringe_hz"], p["stroke_um"]) for p in answer["points"]})


def test_plan_takes_one_number_or_a_sequence_for_each_grid():
    """``fringe_hz=300`` (main: "'int' object is not iterable") is the
    grid [300]; a tuple, a range and an array are lists of numbers. (A
    point's stroke is the true one, samples × step, near the asked.)"""
    one = v2ref.plan(fringe_hz=300, stroke_um=32, **SMALL_PLAN)
    listed = v2ref.plan(fringe_hz=[300.0], stroke_um=[32.0], **SMALL_PLAN)
    assert one["points"] == listed["points"]
    ((fringe_hz, stroke_um),) = _grid_of(one)
    assert fringe_hz == 300.0 and abs(stroke_um - 32.0) < 1.0
    several = v2ref.plan(fringe_hz=np.array([300.0, 500.0]), stroke_um=range(32, 33), **SMALL_PLAN)
    assert _grid_of(several) == [(300.0, stroke_um), (500.0, stroke_um)]
    strokes = v2ref.plan(fringe_hz=(300,), stroke_um=(16, 64.0), **SMALL_PLAN)
    assert len(_grid_of(strokes)) == 2


def test_piston_takes_one_number_or_a_sequence():
    one = v2ref.piston(fringe_hz=300, scans=20)
    assert [r["fringe_hz"] for r in one["results"]] == [300.0]
    several = v2ref.piston(fringe_hz=(300.0, 500), scans=20)
    assert [r["fringe_hz"] for r in several["results"]] == [300.0, 500.0]


@pytest.mark.parametrize("value, error", [(0, ValueError), (True, TypeError), (1.5, TypeError), ("4", TypeError)])
def test_simulate_refuses_a_chunk_that_is_no_count(value, error):
    """Refused whether or not a client is given (main ignored 0 and True
    without one)."""
    with pytest.raises(error, match="^chunk_units: "):
        v2ref.simulate(trials=4, chunk_units=value)


def test_claims_quick_is_a_flag():
    with pytest.raises(TypeError, match="^quick: "):
        v2ref.claims(quick="no")


# The target list from Python: the CLI's reader and parser.
def test_plan_targets_reads_cr_line_ends_and_refuses_what_is_not_utf8(tmp_path):
    path = tmp_path / "list.csv"
    path.write_bytes(b"name,band\rA,Q\rB,H\r")
    rows = v2ref.plan_targets(str(path), **SMALL_PLAN)
    assert [(r["TARGET"], r["line"], r["status"]) for r in rows] == [("A", 2, "error"), ("B", 3, "error")]
    assert rows[0]["reason"].startswith("band: 'Q' is not one of")
    path.write_bytes(b"name,band\nA,H\n\xffB,H\n")
    with pytest.raises(ValueError, match=r"^targets: .*list\.csv.*line 3 .*not UTF-8"):
        v2ref.plan_targets(str(path), **SMALL_PLAN)


def test_plan_targets_says_bounds_readably_and_escapes_control_characters():
    rows = v2ref.plan_targets(
        [{"name": "A", "diameter_mas": float("nan")}, {"name": "\x1b[31mB", "band": "Q"}], **SMALL_PLAN
    )
    assert rows[0]["reason"] == "diameter_mas: NaN is not a finite number; accepted: 0 or more"
    assert rows[1]["status"] == "error"
    assert rows[1]["TARGET"] == "\\u{1b}[31mB"
    assert rows[1]["reason"] == "name: holds the control character \\u{1b}; a cell is printable text"
