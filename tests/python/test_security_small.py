"""Issue 43's smaller findings on the Python side: the OIFITS readers keep
the memory budget of ``V2REF_MAX_MEMORY_GIB``, ``score`` refuses a column
named twice as the CLI does, ``synthesize`` too large for the budget raises
MemoryError instead of aborting the interpreter, and a path whose bytes are
not UTF-8 is refused naming its keyword, not with a codec error."""

from __future__ import annotations

import gzip
import subprocess
import sys

import numpy as np
import pytest

import v2ref

SMALL = dict(rows=8, samples=16, seed=3, reference_blocks=0)


def test_read_oifits_keeps_the_environments_memory_budget(tmp_path, monkeypatch):
    # 900 gzip members of 1 MiB of zeros: a 1 MB file inflating to 900 MiB.
    bomb = tmp_path / "bomb.fits.gz"
    bomb.write_bytes(gzip.compress(bytes(1 << 20), 9) * 900)
    monkeypatch.setenv("V2REF_MAX_MEMORY_GIB", "0.05")
    with pytest.raises(ValueError, match=r"memory budget .*V2REF_MAX_MEMORY_GIB"):
        v2ref.read_oifits(bomb)


def test_score_refuses_a_column_named_twice():
    _, sidecar = v2ref.synthesize(rows=8, samples=16, seed=3)
    estimates = np.full((8, 2), 0.5)
    with pytest.raises(ValueError, match=r"^columns: v2_sq is named twice"):
        v2ref.score(estimates, sidecar, columns=["v2_sq", "v2_sq"])


def test_synthesize_beyond_the_memory_budget_raises_memory_error():
    # In a child under a 4 GB address space: 60 million rows of 32 samples
    # (15 GB, within the documented bounds) aborted the interpreter.
    code = (
        "import resource, v2ref\n"
        "resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))\n"
        "try:\n"
        "    v2ref.synthesize(rows=60_000_000, samples=32, reference_blocks=0)\n"
        "except MemoryError as e:\n"
        "    print('MemoryError:', e)\n"
    )
    run = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        timeout=300,
        env={**__import__("os").environ, "V2REF_MAX_MEMORY_GIB": "1"},
    )
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.startswith("MemoryError: rows: 60000000 rows"), run.stdout
    assert "memory budget" in run.stdout


@pytest.mark.parametrize("call", ["read_oifits", "read_oifits_estimates"])
def test_a_path_that_is_not_utf8_is_refused_naming_its_keyword(tmp_path, call):
    path = bytes(tmp_path) + b"/\xff\xfe.fits"
    with pytest.raises(ValueError, match=r"^path: .* not a UTF-8 path") as info:
        if call == "read_oifits":
            v2ref.read_oifits(path)
        else:
            v2ref.read_oifits_estimates(path, sidecar={})
    assert not isinstance(info.value, UnicodeError)


def test_a_sidecar_path_that_is_not_utf8_is_read(tmp_path):
    rows, sidecar = v2ref.synthesize(**SMALL, out=bytes(tmp_path) + b"/\xff")
    est = v2ref.estimate(rows, sidecar=sidecar)
    report = v2ref.score(est, bytes(tmp_path) + b"/\xff.json")
    assert report["rows"] == 8
