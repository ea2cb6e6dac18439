"""Issue 53, checkpoints and target lists: a checkpoint entry that is
damaged (a bit flipped), another row's or list's, stale (its spectrum CSV
edited) or another user's is never used; every row of a target list comes
back whatever its name; ``client=`` and ``checkpoint=`` are refused by
name; a task carries its row, not the list. No cluster here (the Dask
paths share this code: tests/python/test_dask.py runs them)."""

import os
import pickle

import pytest

import v2ref
from v2ref import dask as v2dask

#: 6 units of 8192 rows of 32 samples, cut in 3 ranges of 2 units.
SMALL = dict(trials=6 * 8192 - 100, samples=32, seed=5, threads=1)

#: As tests/python/test_plan_targets.py: one grid point, a short Monte Carlo.
SHARED = dict(
    wavelength_um=1.65, bandwidth_nm=300.0, fringe_hz=[500.0], stroke_um=[32.0], scans=50,
    aperture_m=1.8, target_sigma_v2=1e-2, seed=7, throughput=0.01,
)
ROWS = [
    {"name": "alpha", "magnitude": 5.0, "band": "H"},
    {"name": "beta", "magnitude": 5.5, "band": "H"},
    {"name": "gamma", "magnitude": 6.0, "band": "H"},
]
#: A user that is not this one (the tests that give a file away run as root).
OTHER_UID = 65534
as_root = pytest.mark.skipif(os.geteuid() != 0, reason="gives a file to another user: needs root")


def bits(x):
    if isinstance(x, float):
        return x.hex()
    if isinstance(x, dict):
        return {k: bits(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [bits(v) for v in x]
    return x


def entries(folder):
    return sorted(p for p in folder.iterdir() if not p.name.startswith("."))


def flip(path, at):
    data = bytearray(path.read_bytes())
    data[at] ^= 0x01
    path.write_bytes(bytes(data))


# --- partial results --------------------------------------------------------


@pytest.mark.parametrize("at", [40, 99, -16], ids=["the first result", "a high byte", "the last result"])
def test_a_partial_with_one_bit_flipped_is_refused_by_name(tmp_path, at):
    folder = tmp_path / "ck"
    v2ref.simulate(**SMALL, checkpoint=folder, chunk_units=2)
    victim = entries(folder)[1]
    flip(victim, at)
    with pytest.raises(ValueError, match=f"checkpoint: .*{victim.name}.*checksum"):
        v2ref.simulate(**SMALL, checkpoint=folder, chunk_units=2)


def _counting(monkeypatch):
    """The ranges computed from now on (``v2ref.dask._run_range`` wrapped)."""
    ran = []
    run = v2dask._run_range

    def counted(command, args, start, end):
        ran.append((start, end))
        return run(command, args, start, end)

    monkeypatch.setattr(v2dask, "_run_range", counted)
    return ran


@as_root
def test_a_partial_of_another_user_is_not_read_and_its_units_computed_again(tmp_path, monkeypatch):
    one = v2ref.simulate(**SMALL)
    folder = tmp_path / "ck"
    v2ref.simulate(**SMALL, checkpoint=folder, chunk_units=2)
    planted = entries(folder)[0]
    # Another user's file at this request's name, damaged: never trusted,
    # never used, its units computed again.
    flip(planted, 40)
    os.chown(planted, OTHER_UID, OTHER_UID)
    ran = _counting(monkeypatch)
    with pytest.warns(UserWarning, match=f"{planted.name}.*another user"):
        again = v2ref.simulate(**SMALL, checkpoint=folder, chunk_units=2)
    assert ran == [(0, 2)]
    assert bits(again) == bits(one)
    assert planted.stat().st_uid == OTHER_UID, "another user's entry is left as it is"


# --- target list records -----------------------------------------------------


def _forge(path, edit):
    """``path``'s record with its JSON body edited by ``edit`` (the digest
    in front, if any, left as it was)."""
    import json

    data = path.read_bytes()
    at = data.index(b"{")
    body = json.loads(data[at:])
    edit(body)
    path.write_bytes(data[:at] + json.dumps(body).encode())


@pytest.mark.parametrize(
    "edit",
    [
        lambda rec, other: rec.update(table=[]),
        lambda rec, other: rec.update(table=rec["table"] * 2),
        lambda rec, other: rec.update(table=other["table"]),
    ],
    ids=["empty table", "table doubled", "another row's table"],
)
def test_a_record_edited_is_refused_not_a_row_dropped_doubled_or_taken(tmp_path, edit):
    import json

    folder = tmp_path / "ck"
    v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
    first, second = entries(folder)[:2]
    data = second.read_bytes()
    other = json.loads(data[data.index(b"{"):])
    _forge(first, lambda rec: edit(rec, other))
    with pytest.raises(ValueError, match=f"checkpoint: .*{first.name}"):
        v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)


def test_a_record_forged_with_its_digest_is_still_checked_against_its_row(tmp_path):
    from v2ref import _checkpoint

    folder = tmp_path / "ck"
    v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
    first, second = entries(folder)[:2]
    import json

    def body(p):
        data = p.read_bytes()
        return json.loads(data[data.index(b"{"):])

    mine, other = body(first), body(second)
    # A digest that matches (a writer of the folder can forge any): an
    # empty table, a doubled one, another row's are still refused.
    for table in ([], mine["table"] * 2, other["table"]):
        first.write_bytes(_checkpoint.record_bytes(mine["key"], 0, mine["line"], mine["name"], table))
        with pytest.raises(ValueError, match=f"{first.name}.*(one table row|another line)"):
            v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
    # So is a body nested past Python's recursion limit.
    nested = b"[" * 100_000
    first.write_bytes(_checkpoint._RECORD_MAGIC + _checkpoint._record_digest(nested).encode() + b"\n" + nested)
    with pytest.raises(ValueError, match=f"{first.name}.*no readable record"):
        v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)


@pytest.mark.parametrize(
    "content",
    [b"\xff\xfe not utf-8", b"{not json", b"[" * 100_000],
    ids=["not UTF-8", "not JSON", "nested past the recursion limit"],
)
def test_an_unreadable_record_is_refused_naming_it(tmp_path, content):
    folder = tmp_path / "ck"
    v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
    victim = entries(folder)[0]
    victim.write_bytes(content)
    with pytest.raises(ValueError, match=f"checkpoint: .*{victim.name}"):
        v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)


def test_an_edited_spectrum_csv_plans_the_rows_again(tmp_path):
    spectrum = tmp_path / "s.csv"
    kw = dict(SHARED, spectrum_csv=spectrum)
    del kw["wavelength_um"], kw["bandwidth_nm"]
    rows = [{"name": "alpha"}, {"name": "beta", "diameter_mas": 2.0}]
    spectrum.write_text("wavelength_um,weight\n1.5,1\n1.65,2\n1.8,1\n")
    folder = tmp_path / "ck"
    before = v2ref.plan_targets(rows, **kw, checkpoint=folder)
    spectrum.write_text("wavelength_um,weight\n1.5,1\n1.65,0.2\n1.8,1\n")
    fresh = v2ref.plan_targets(rows, **kw)
    assert bits(fresh) != bits(before), "the edit changes the plan"
    assert bits(v2ref.plan_targets(rows, **kw, checkpoint=folder)) == bits(fresh)


@as_root
def test_a_record_of_another_user_is_not_read_and_its_row_planned_again(tmp_path):
    folder = tmp_path / "ck"
    whole = v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder)
    planted = entries(folder)[1]
    _forge(planted, lambda rec: rec.update(table=[]))
    os.chown(planted, OTHER_UID, OTHER_UID)
    done = []
    with pytest.warns(UserWarning, match=f"{planted.name}.*another user"):
        again = v2ref.plan_targets(ROWS, **SHARED, checkpoint=folder, progress=lambda d, t: done.append(d))
    assert done == [3], "the one row of another user's entry planned again"
    assert bits(again) == bits(whole)


def test_a_planted_temporary_name_does_not_stop_a_run(tmp_path):
    folder = tmp_path / "ck"
    one = v2ref.simulate(**SMALL, checkpoint=folder, chunk_units=2)
    first = entries(folder)[0]
    first.unlink()
    # The names a temporary of this process would take (25b05bd: a serial).
    for serial in range(1, 4):
        (folder / f".v2ref-tmp-{os.getpid()}-{serial}-{first.name}").write_bytes(b"x")
    assert bits(v2ref.simulate(**SMALL, checkpoint=folder, chunk_units=2)) == bits(one)
    assert first.exists()


# --- rows, keywords ----------------------------------------------------------


@pytest.mark.parametrize(
    "rows",
    [
        [{"name": "#5 Cen"}, {"name": None}, {"name": "beta"}],
        [{"name": "#5 Cen", "magnitude": 5.0, "band": "H"}, {"name": None, "magnitude": 5.0, "band": "H"}, {"name": "beta"}],
    ],
    ids=["name only", "with magnitudes"],
)
def test_every_row_comes_back_whatever_its_name(rows):
    table = v2ref.plan_targets(rows, **SHARED)
    assert [r["line"] for r in table] == [2, 3, 4]
    assert table[0]["TARGET"] == "#5 Cen" and table[0]["status"] != "error"
    assert table[1]["status"] == "error" and "name" in table[1]["reason"]
    assert table[2]["TARGET"] == "beta"


@pytest.mark.parametrize("call", ["plan_targets", "simulate", "piston", "plan"])
@pytest.mark.parametrize("keyword", ["client", "checkpoint"])
def test_client_and_checkpoint_of_the_wrong_kind_are_refused_by_name(call, keyword):
    run = {
        "plan_targets": lambda **kw: v2ref.plan_targets(ROWS, **SHARED, **kw),
        "simulate": lambda **kw: v2ref.simulate(**SMALL, **kw),
        "piston": lambda **kw: v2ref.piston(fringe_hz=[300.0], scans=20, samples=32, **kw),
        # Without verify: nothing would run on them, still refused.
        "plan": lambda **kw: v2ref.plan(fringe_hz=[500.0], stroke_um=[32.0], scans=50, **kw),
    }[call]
    with pytest.raises(TypeError, match=f"^{keyword}: 42 is not"):
        run(**{keyword: 42})


def test_a_checkpoint_folder_that_cannot_be_made_is_refused_before_planning(tmp_path, monkeypatch):
    missing = tmp_path / "no" / "ck"
    done = []
    with pytest.raises(ValueError, match="checkpoint: .*cannot be made"):
        v2ref.plan_targets(ROWS, **SHARED, checkpoint=missing, progress=lambda d, t: done.append(d))
    assert done == []
    planned = []
    monkeypatch.setattr(v2ref._plan._v2ref, "plan", lambda **kw: planned.append(kw))
    with pytest.raises(ValueError, match="checkpoint: .*cannot be made"):
        v2ref.plan(**{k: v for k, v in SHARED.items() if k != "throughput"}, verify=True, checkpoint=missing)
    assert planned == [], "refused before the plan ran"


# --- linear cost ---------------------------------------------------------------


def _payloads(monkeypatch, rows):
    """The pickled size of each task's arguments when ``rows`` are planned
    with ``progress=`` (the rows' plans replaced by a stub: only what a
    task is given is measured)."""
    sizes = []

    def task(*args):
        sizes.append(len(pickle.dumps(args)))
        return [{"TARGET": "stub"}]

    monkeypatch.setattr(v2dask, "_target_rows", task)
    v2ref.plan_targets(rows, **SHARED, progress=lambda d, t: None)
    return sizes


def test_a_task_carries_its_row_not_the_list(monkeypatch):
    few = _payloads(monkeypatch, [{"name": f"star {i}", "magnitude": 5.0, "band": "H"} for i in range(4)])
    many = _payloads(monkeypatch, [{"name": f"star {i}", "magnitude": 5.0, "band": "H"} for i in range(400)])
    assert len(few) == 4 and len(many) == 400
    # The list 100 times longer: a task's arguments grow by a row number's
    # digits at most, not by the list (400 rows are some 8 kB of text).
    assert max(many) <= max(few) + 16
