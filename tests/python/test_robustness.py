"""Python keeps the CLI's rules (issue 35): ``synthesize(out=...)`` writes
with the CLI's writers (no overwrite without ``force=True``, never through
a link, a set whole or refused, names as given), a call on a daemon thread
never aborts the interpreter at exit, masked arrays are refused by name,
and an integer too large for its keyword names the keyword."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from pathlib import Path

import numpy as np
import pytest

import v2ref

SMALL = dict(rows=8, samples=16, seed=3, reference_blocks=0)


def test_out_is_not_replaced_without_force_and_never_through_a_link(tmp_path):
    out = tmp_path / "set"
    rows, _ = v2ref.synthesize(out=out, **SMALL)
    before = (out.with_suffix(".npy").read_bytes(), out.with_suffix(".json").read_bytes())
    with pytest.raises(ValueError, match=r"^out: .*set\.npy: exists .*--force"):
        v2ref.synthesize(out=out, **{**SMALL, "seed": 4})
    assert (out.with_suffix(".npy").read_bytes(), out.with_suffix(".json").read_bytes()) == before
    v2ref.synthesize(out=out, force=True, **{**SMALL, "seed": 4})
    assert not np.array_equal(np.load(out.with_suffix(".npy")), rows)
    target = tmp_path / "elsewhere.txt"
    target.write_text("mine\n")
    (tmp_path / "link.npy").symlink_to(target)
    with pytest.raises(ValueError, match="symbolic link"):
        v2ref.synthesize(out=tmp_path / "link", force=True, **SMALL)
    assert target.read_text() == "mine\n"
    # Nothing but the sets, the link and its target: no temporary, no lock.
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "elsewhere.txt", "link.npy", "set.json", "set.npy"]


def test_out_keeps_a_non_utf8_name_as_given(tmp_path):
    out = os.fsencode(tmp_path) + b"/s\xff\xfe"
    rows, _ = v2ref.synthesize(out=out, **SMALL)
    assert sorted(os.listdir(os.fsencode(tmp_path))) == [b"s\xff\xfe.json", b"s\xff\xfe.npy"]
    np.testing.assert_array_equal(np.load(out + b".npy"), rows)


def test_threads_writing_one_out_leave_one_whole_set(tmp_path):
    # Four threads race to write one set, 30 times over. The writers before
    # issue 35 left the rows of one seed beside the sidecar of another in
    # 7 of 20 such races (measured): all 30 whole by chance, 3e-6.
    for race in range(30):
        out = tmp_path / str(race) / "set"
        out.parent.mkdir()
        errors = []

        def write(seed):
            try:
                v2ref.synthesize(out=out, force=True, **{**SMALL, "rows": 20000, "seed": seed})
            except ValueError as e:
                errors.append(str(e))

        threads = [threading.Thread(target=write, args=(s,)) for s in range(10, 14)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for e in errors:
            assert e.startswith("out: ") and "is writing it now" in e, e
        # The rows on disk are those of the seed the sidecar beside them states.
        written = np.load(out.with_suffix(".npy"))
        sidecar = json.loads(out.with_suffix(".json").read_text())
        rows, _ = v2ref.synthesize(**{**SMALL, "rows": 20000, "seed": sidecar["seed"]})
        np.testing.assert_array_equal(written, rows, err_msg=f"race {race}")


def test_a_call_on_a_daemon_thread_does_not_abort_the_interpreter_at_exit():
    code = (
        "import threading, time, v2ref\n"
        "for f in (lambda: v2ref.simulate(trials=10**8), lambda: v2ref.piston(scans=10**7)):\n"
        "    threading.Thread(target=f, daemon=True).start()\n"
        "time.sleep(0.5)\n"
    )
    p = subprocess.run([sys.executable, "-W", "ignore", "-c", code], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, (p.returncode, p.stderr[-500:])


def test_a_masked_array_is_refused_by_name():
    rows = np.ma.masked_less(np.full((4, 16), 100.0) + np.arange(16), 101.0)
    with pytest.raises(TypeError, match=r"^interferograms: a masked array"):
        v2ref.estimate(rows)
    with pytest.raises(TypeError, match=r"^calibrator: a masked array"):
        v2ref.estimate(rows.data, calibrator=rows)


@pytest.mark.parametrize(
    "call, keyword",
    [
        (lambda: v2ref.synthesize(rows=2**70), "rows"),
        (lambda: v2ref.simulate(trials=2**70), "trials"),
        (lambda: v2ref.simulate(seed=2**64), "seed"),
        (lambda: v2ref.simulate(photons=10**400), "photons"),
        (lambda: v2ref.piston(fringe_hz=10**400, scans=4), "fringe_hz"),
    ],
)
def test_an_integer_too_large_names_its_keyword(call, keyword):
    with pytest.raises(ValueError, match=rf"^{keyword}: "):
        call()


def test_a_memory_mapped_array_is_refused_at_its_first_bad_row(tmp_path):
    # 1 GiB of rows without light (a sparse file): refused at row 1 once
    # its block is read, without reading (mapping in) the rest.
    import resource

    rows = np.lib.format.open_memmap(tmp_path / "dark.npy", mode="w+", dtype="<f8", shape=(1 << 20, 128))
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    with pytest.raises(ValueError, match=r"^interferograms: .*row 1\b"):
        v2ref.estimate(rows)
    grown_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
    assert grown_kib < 256 << 10, f"{grown_kib} KiB resident for a refusal at row 1"


def test_the_docs_say_that_ctrl_c_stops_estimate():
    # docs/python.md said that `estimate` runs to the end; it stops at its
    # next checkpoint as the other long calls do.
    docs = (Path(__file__).resolve().parents[2] / "docs" / "python.md").read_text()
    ctrl_c = next(p for p in docs.split("\n- ") if p.startswith("**Ctrl-C**"))
    assert "`estimate`" in ctrl_c and "run to the end" not in ctrl_c, ctrl_c
