"""Issue 53 from Python: a lock name taken by a hard link is refused by every
writer and the linked file kept; a FIFO given where a file is read is
refused at once (each call runs in a child process killed after 60 s, so a
reader that waits fails the test instead of hanging it); a sidecar is read
with the CLI's bound; a path given to ``score`` where an array is expected
is refused naming the keyword. See docs/threat-model.md."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import v2ref

SMALL = dict(rows=8, samples=16, seed=3, reference_blocks=0)


def fnv1a(text: str) -> str:
    h = 0xCBF29CE484222325
    for b in text.encode():
        h = ((h ^ b) * 0x100000001B3) % (1 << 64)
    return f"{h:016x}"


@pytest.fixture
def folder(tmp_path):
    _, sidecar = v2ref.synthesize(out=tmp_path / "set", **SMALL)
    os.mkfifo(tmp_path / "fifo.json")
    os.mkfifo(tmp_path / "fifo.csv")
    return tmp_path, sidecar


def run_child(code: str, cwd: Path) -> subprocess.CompletedProcess:
    """``code`` run by a child Python in ``cwd``, killed after 60 s."""
    try:
        return subprocess.run(
            [sys.executable, "-c", "import numpy as np, v2ref\n" + code],
            cwd=cwd,
            capture_output=True,
            text=True,
            timeout=60,
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"waited on a FIFO (killed after 60 s): {code}")


@pytest.mark.parametrize(
    "call",
    [
        "v2ref.estimate(np.zeros((8, 16)), sidecar='fifo.json')",
        "v2ref.score(np.zeros(8), sidecar='fifo.json')",
        "v2ref.read_oifits_estimates('set.truth.fits', sidecar='fifo.json')",
        "v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, spectrum_csv='fifo.csv')",
    ],
)
def test_a_fifo_is_refused_at_once_naming_it(folder, call):
    """(On 25b05bd each call waited for a writer for ever.)"""
    d, sidecar = folder
    v2ref.write_oifits_truth(d / "set.truth.fits", sidecar=sidecar, force=True)
    r = run_child(
        f"try:\n    {call}\nexcept (ValueError, TypeError, OSError) as e:\n    print(type(e).__name__, e)\n",
        d,
    )
    assert r.returncode == 0, r.stderr
    assert r.stdout.startswith("ValueError") and "fifo." in r.stdout, r.stdout
    assert "not a regular file" in r.stdout, r.stdout


def test_a_sidecar_beyond_the_clis_bound_is_refused_naming_it(folder):
    """A 17 MiB sidecar: refused naming the bound, as `estimate --sidecar`
    refuses it (on 25b05bd read whole: 600 MiB took 1.8 GB)."""
    d, _ = folder
    big = d / "big.json"
    with open(big, "wb") as f:
        f.truncate(17 << 20)
    with pytest.raises(ValueError, match=r"^sidecar: .*big\.json.*larger than 16777216 bytes"):
        v2ref.estimate(np.zeros((8, 16)), sidecar=big)


def test_a_path_where_score_takes_an_array_is_refused_naming_the_keyword(folder):
    """(On 25b05bd: "0-D array of shape ()".)"""
    d, sidecar = folder
    for path in ["est.csv", d / "est.npy", "est.oidata"]:
        with pytest.raises(TypeError, match=r"^estimates: .*is a path.*\.fits"):
            v2ref.score(path, sidecar=sidecar)


def lock_of(d: Path, name: str) -> Path:
    return d / f".v2ref-lock-{fnv1a(name)}"


@pytest.mark.parametrize("writer", ["synthesize", "write_oifits", "plan"])
def test_a_hard_link_at_a_lock_name_is_refused_and_its_file_kept(folder, writer):
    """(On 25b05bd the writer emptied the linked file and wrote its process
    id in it.)"""
    d, sidecar = folder
    notes = d / "notes.txt"
    notes.write_bytes(b"a user's notes\n")
    calls = {
        "synthesize": ("new.npy", lambda: v2ref.synthesize(out=d / "new", **SMALL)),
        "write_oifits": (
            "est.fits",
            lambda: v2ref.write_oifits(d / "est.fits", v2_sq=np.zeros(8), sidecar=sidecar),
        ),
        "plan": (
            "plan.fits",
            lambda: v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, oifits=d / "plan.fits"),
        ),
    }
    name, call = calls[writer]
    os.link(notes, lock_of(d, name))
    with pytest.raises(ValueError, match=r"\.v2ref-lock-.*not a file v2ref made"):
        call()
    assert notes.read_bytes() == b"a user's notes\n"
