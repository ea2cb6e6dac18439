"""Issue 43 from Python: the OIFITS writers keep the set rules (an existing
file replaced only with ``force=True``, never through a link), an ``out``
that names a folder is refused, and a reader writes nothing whatever it
finds beside the file it reads (a forged commit record of the format before
issue 43 names a decoy outside the test's folder). See
docs/threat-model.md."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

import v2ref

SMALL = dict(rows=8, samples=16, seed=3, reference_blocks=0)


def snapshot(d: Path):
    """Every entry under ``d`` (not followed): kind, size, mtime, bytes."""
    out = []
    for p in sorted(d.rglob("*")):
        st = p.lstat()
        data = p.read_bytes() if p.is_file() and not p.is_symlink() else b""
        out.append((str(p), st.st_mode, st.st_size, st.st_mtime_ns, data))
    return out


@pytest.fixture
def scene(tmp_path):
    shared, outside = tmp_path / "shared", tmp_path / "outside"
    shared.mkdir()
    outside.mkdir()
    (outside / "decoy.txt").write_text("decoy\n")
    _, sidecar = v2ref.synthesize(out=shared / "set", **SMALL)
    return shared, outside, sidecar


@pytest.mark.parametrize("writer", ["write_oifits", "write_oifits_truth"])
def test_an_oifits_writer_replaces_only_with_force_and_never_through_a_link(scene, writer):
    shared, outside, sidecar = scene
    kw = dict(sidecar=sidecar)
    if writer == "write_oifits":
        kw["v2_sq"] = np.zeros(SMALL["rows"])
    write = getattr(v2ref, writer)
    path = shared / "x.fits"
    write(path, **kw)
    before = path.read_bytes()
    with pytest.raises(ValueError, match=r"^path: .*x\.fits: exists .*--force"):
        write(path, **kw)
    assert path.read_bytes() == before
    write(path, force=True, **kw)
    (shared / "link.fits").symlink_to(outside / "decoy.txt")
    with pytest.raises(ValueError, match="symbolic link"):
        write(shared / "link.fits", force=True, **kw)
    assert (outside / "decoy.txt").read_text() == "decoy\n"
    with pytest.raises(TypeError, match="force"):
        write(path, force=1, **kw)


def test_plan_refuses_an_existing_oifits_without_force(tmp_path):
    path = tmp_path / "plan.fits"
    path.write_bytes(b"mine")
    with pytest.raises(ValueError, match=r"^oifits: .*plan\.fits: exists .*--force"):
        v2ref.plan(fringe_hz=[300], stroke_um=[32], scans=64, oifits=path)
    assert path.read_bytes() == b"mine"


@pytest.mark.parametrize("out", ["d/", "d/.", "new/"])
def test_an_out_that_names_a_folder_is_refused(tmp_path, out):
    (tmp_path / "d").mkdir()
    with pytest.raises(ValueError, match=r"^out: .*names a folder"):
        v2ref.synthesize(out=str(tmp_path) + "/" + out, **SMALL)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d"]
    assert list((tmp_path / "d").iterdir()) == []


def fnv1a(text: str) -> str:
    h = 0xCBF29CE484222325
    for b in text.encode():
        h = ((h ^ b) * 0x100000001B3) % (1 << 64)
    return f"{h:016x}"


def test_a_reader_writes_nothing_beside_a_forged_record(scene):
    shared, outside, sidecar = scene
    truth = shared / "set.truth.fits"
    v2ref.write_oifits_truth(truth, sidecar=sidecar)
    real = Path(os.path.realpath(shared))
    hexa = lambda p: bytes(str(p), "utf-8").hex()
    text = (f"v2ref commit record 1\npid 4194304\nforce 1\nmember {hexa(real / truth.name)} "
            f"{hexa(outside / 'decoy.txt')} {hexa(outside / 'decoy.txt')}\n")
    (shared / f".v2ref-journal-{fnv1a(truth.name)}").write_text(f"{text}sum {fnv1a(text)}\n")
    before, decoys = snapshot(shared), snapshot(outside)
    v2ref.read_oifits(truth)
    v2ref.read_oifits_estimates(truth, sidecar=shared / "set.json")
    assert snapshot(shared) == before
    assert snapshot(outside) == decoys
