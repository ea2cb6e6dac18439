"""``v2ref.plan_targets``: the target list of ``v2ref plan --targets``
from a list of dicts, an astropy Table or a file, with ``plan``'s keywords
shared; the numbers are the CLI's, bit for bit, and a bad row is marked,
not raised."""

import csv
import io
import subprocess

import pytest

import v2ref
from conftest import release_binary

# One grid point of a bright H-band source, a short Monte Carlo, a target
# every row reaches (well under a second a row).
SHARED = dict(
    wavelength_um=1.65,
    bandwidth_nm=300.0,
    fringe_hz=[500.0],
    stroke_um=[32.0],
    scans=50,
    aperture_m=1.8,
    target_sigma_v2=1e-2,
    seed=7,
    throughput=0.01,
)
FLAGS = [
    "--wavelength-um", "1.65", "--bandwidth-nm", "300", "--fringe-hz", "500",
    "--stroke-um", "32", "--scans", "50", "--aperture-m", "1.8",
    "--target-sigma-v2", "1e-2", "--seed", "7", "--throughput", "0.01", "--quiet",
]
ROWS = [
    {"name": "alpha", "magnitude": 5.0, "band": "H", "diameter_mas": 1.0, "ra_deg": 10.5, "dec_deg": -20.0},
    {"name": "beta", "magnitude": "5x", "band": "H"},
    {"name": "gamma", "magnitude": 6.0, "band": "h", "diameter_mas": None},
]


def _number(v):
    return None if v == "" else float(v)


def test_a_list_of_dicts_is_planned_and_a_bad_row_marked():
    rows = v2ref.plan_targets(ROWS, **SHARED)
    assert [r["TARGET"] for r in rows] == ["alpha", "beta", "gamma"]
    assert [r["status"] for r in rows] == ["ok", "error", "ok"]
    # Line of the same rows written as CSV under a header: index + 2.
    assert rows[1]["line"] == 3
    assert rows[1]["reason"].startswith("magnitude: '5x' is not a number")
    assert rows[0]["RAEP0"] == 10.5 and rows[0]["DECEP0"] == -20.0
    assert rows[2]["diameter_mas"] == 43.0, "a None cell takes the shared diameter"
    assert rows[0]["time_s"] > 0 and rows[0]["estimator"] == "v1"


@pytest.mark.needs_bin
def test_the_numbers_are_the_clis_from_a_table_and_from_a_file(tmp_path):
    from astropy.table import Table

    good = [ROWS[0], ROWS[2]]
    table = Table(rows=[[r["name"], r["magnitude"], r["band"]] for r in good], names=["name", "magnitude", "band"])
    from_table = v2ref.plan_targets(table, **SHARED)
    path = tmp_path / "list.csv"
    path.write_text("name,magnitude,band\nalpha,5,H\ngamma,6,h\n")
    from_file = v2ref.plan_targets(path, **SHARED)
    out = subprocess.run(
        [str(release_binary()), "plan", "--targets", str(path), *FLAGS],
        capture_output=True, text=True, check=True,
    ).stdout
    cli = list(csv.DictReader(io.StringIO(out)))
    assert len(cli) == len(from_table) == len(from_file) == 2
    for c, t, f in zip(cli, from_table, from_file):
        assert t == f, "a Table and a file give the same rows"
        for k in ("time_s", "scans", "sigma_v2", "sigma_v2_lower", "fringe_hz", "photon_rate_per_s"):
            assert _number(c[k]) == t[k], k
        assert int(c["seed"]) == t["seed"]


def test_bad_lists_and_keywords_are_refused_by_name():
    with pytest.raises(TypeError, match="^targets"):
        v2ref.plan_targets(42, **SHARED)
    with pytest.raises(ValueError, match="^targets"):
        v2ref.plan_targets([{"name": "a", "colour": "red"}], **SHARED)
    with pytest.raises(TypeError, match="^oifits"):
        v2ref.plan_targets(ROWS, oifits="x.fits", **SHARED)
    with pytest.raises(TypeError, match="plan_targets"):
        v2ref.plan_targets(ROWS, no_such_keyword=1, **SHARED)
    with pytest.raises(ValueError, match=r"^targets\[0\]\['name'\]"):
        v2ref.plan_targets([{"name": "a\nb"}], **SHARED)


@pytest.mark.needs_bin
def test_an_instrument_preset_fills_what_was_not_given_as_the_cli(tmp_path):
    # The preset sets the band, apertures, throughput and detector; the
    # read noise given overrides it; the rows' magnitudes take the preset's
    # throughput (none given), as `plan --targets --instrument` does.
    path = tmp_path / "list.csv"
    path.write_text("name,magnitude,band\nalpha,4,H\n")
    keywords = dict(fringe_hz=[500.0], stroke_um=[32.0], scans=50, target_sigma_v2=1e-2, seed=7)
    rows = v2ref.plan_targets(path, instrument="vlti-pionier", read_noise=2.5, **keywords)
    out = subprocess.run(
        [str(release_binary()), "plan", "--targets", str(path), "--instrument", "vlti-pionier",
         "--read-noise", "2.5", "--fringe-hz", "500", "--stroke-um", "32", "--scans", "50",
         "--target-sigma-v2", "1e-2", "--seed", "7", "--quiet"],
        capture_output=True, text=True, check=True,
    ).stdout
    (cli,) = list(csv.DictReader(io.StringIO(out)))
    assert rows[0]["status"] == "ok", rows[0]["reason"]
    for k in ("time_s", "scans", "sigma_v2", "photon_rate_per_s"):
        assert _number(cli[k]) == rows[0][k], k
    without = v2ref.plan_targets(path, instrument="vlti-pionier", **keywords)
    assert without[0]["sigma_v2"] != rows[0]["sigma_v2"], "the read noise given counts"


def bits(x):
    """``x`` with every float as its exact hex form (so == compares bits)."""
    if isinstance(x, float):
        return x.hex()
    if isinstance(x, dict):
        return {k: bits(v) for k, v in x.items()}
    if isinstance(x, list):
        return [bits(v) for v in x]
    return x


def test_progress_reports_each_target_and_keeps_the_table(tmp_path, capsys):
    whole = v2ref.plan_targets(ROWS, **SHARED)
    seen = []
    rows = v2ref.plan_targets(ROWS, **SHARED, progress=lambda done, total: seen.append((done, total)))
    assert seen == [(1, 3), (2, 3), (3, 3)]
    assert bits(rows) == bits(whole)  # planned a row at a time: the same table
    # A path is read once and planned a row at a time: the file's table.
    path = tmp_path / "list.csv"
    path.write_text("# a comment\nname,magnitude,band\nalpha,5,H\r\n\ngamma,6,h\n")
    assert bits(v2ref.plan_targets(path, **SHARED, progress=True)) == bits(v2ref.plan_targets(path, **SHARED))
    err = capsys.readouterr().err.splitlines()
    assert err[-1].startswith("plan_targets: 2/2 targets, ") and err[-1].endswith(" elapsed, done")
    with pytest.raises(TypeError, match="progress"):
        v2ref.plan_targets(ROWS, **SHARED, progress="yes")


def test_the_progress_line_is_at_most_one_a_second_with_the_time_left():
    import io

    from v2ref._progress import Line

    now = [100.0]
    out = io.StringIO()
    line = Line(stream=out, clock=lambda: now[0])
    for done, t in [(1, 101.0), (2, 101.5), (3, 102.5), (4, 102.6)]:
        now[0] = t
        line(done, 4)
    # The second within a second of the first: not shown; the last always.
    assert out.getvalue().splitlines() == [
        "plan_targets: 1/4 targets, 0:01 elapsed, about 0:03 left",
        "plan_targets: 3/4 targets, 0:02 elapsed, about 0:01 left",
        "plan_targets: 4/4 targets, 0:03 elapsed, done",
    ]


def test_a_checkpoint_keeps_each_row_and_a_rerun_plans_only_the_missing(tmp_path):
    whole = v2ref.plan_targets(ROWS, **SHARED)
    folder = tmp_path / "ck"
    planned = []
    count = lambda done, total: planned.append(done)  # noqa: E731
    assert bits(v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder, progress=count)) == bits(whole)
    entries = sorted(p.name for p in folder.iterdir())
    assert len(entries) == 3 and len(planned) == 3
    # One row's entry lost: only that row is planned again, the others are
    # read (their files untouched), and the table has the same bits.
    (folder / entries[1]).unlink()
    kept = {n: (folder / n).stat().st_ino for n in (entries[0], entries[2])}
    planned.clear()
    assert bits(v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder, progress=count)) == bits(whole)
    assert planned == [3], "one row planned, counted after the two read"
    assert {n: (folder / n).stat().st_ino for n in kept} == kept
    # Other arguments: another key, nothing of this list's entries read.
    other = dict(SHARED, seed=8)
    planned.clear()
    v2ref.plan_targets(ROWS, **other, checkpoint=folder, progress=count)
    assert len(planned) == 3
    # An entry that is a link, or that names another row, is refused.
    victim = folder / entries[0]
    victim.unlink()
    victim.symlink_to(folder / entries[2])
    with pytest.raises(ValueError, match="checkpoint: .* link is never followed"):
        v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
    victim.unlink()
    victim.write_bytes((folder / entries[2]).read_bytes())
    with pytest.raises(ValueError, match="checkpoint: .* record of another list, keywords or row"):
        v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
