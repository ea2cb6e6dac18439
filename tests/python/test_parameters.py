"""The physical inputs are declared once, in the library
(``v2ref::parameters``): their names, defaults, units and ranges. What the
package holds of them is generated from that declaration
(``scripts/regenerate.sh``): ``_declaration.py``, the physical keyword
arguments of each signature (checked by the Rust test
``generated_files_are_the_declarations``) and the stub. These tests check
the generated output against the built library and the package's source,
and that each keyword reaches the library.
"""

from __future__ import annotations

import ast
import importlib.util
import inspect
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import v2ref
from v2ref import _declaration, _v2ref

ROOT = Path(__file__).resolve().parents[2]
STUB = ROOT / "python" / "v2ref" / "__init__.pyi"

# The public functions that take physical keyword arguments.
FUNCTIONS = ["estimate", "synthesize", "simulate", "bias", "snr", "piston", "plan"]
# Their keyword arguments named as a physical input that take something
# else: plan's grids, piston's list of frequencies.
NOT_PHYSICAL = {"plan": {"fringe_hz", "stroke_um"}, "piston": {"fringe_hz"}}


def test_the_generated_declaration_is_the_librarys():
    """``_declaration.py`` holds what the built library declares: names in
    order, defaults, help texts (a stale generated file, or a build of
    another declaration, fails)."""
    assert list(_declaration.DEFAULTS) == list(_v2ref.PHYSICAL_KEYWORDS)
    assert _declaration.DEFAULTS == _v2ref.PHYSICAL_DEFAULTS
    for p in _v2ref.PHYSICAL_PARAMETERS:
        assert _declaration.DOCS[p["name"]] == p["doc"], p["name"]
        assert _declaration.UNSET_DOCS[p["name"]] == p["unset_doc"], p["name"]
    assert len(_declaration.DEFAULTS) == 24


def _load_stub_script():
    spec = importlib.util.spec_from_file_location("stub_script", ROOT / "scripts" / "stub.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_stub_is_generated_from_the_source():
    """The stub is what ``scripts/stub.py`` makes of the package's source."""
    done = subprocess.run(
        [sys.executable, str(ROOT / "scripts" / "stub.py"), "--check"], capture_output=True, text=True
    )
    assert done.returncode == 0, done.stdout + done.stderr


def test_a_changed_source_changes_the_stub(tmp_path, monkeypatch):
    """The check's power: a default, a docstring and a declared help text
    changed in a copy of the package each change the stub made."""
    script = _load_stub_script()
    committed = STUB.read_text(encoding="utf-8")
    package = tmp_path / "v2ref"
    shutil.copytree(ROOT / "python" / "v2ref", package)
    monkeypatch.setattr(script, "PACKAGE", package)
    assert script.stub() == committed
    plants = [
        ("__init__.py", "    rows: int = 1000,", "    rows: int = 1001,"),
        ("__init__.py", "Number of rows (scans)", "Number of rows"),
        ("_declaration.py", "Centre wavelength λ0", "Center wavelength λ0"),
    ]
    for name, old, new in plants:
        path = package / name
        text = path.read_text(encoding="utf-8")
        assert old in text, (name, old)
        path.write_text(text.replace(old, new, 1), encoding="utf-8")
        assert script.stub() != committed, (name, new)
        path.write_text(text, encoding="utf-8")


def _stub_functions():
    """{name: ast.FunctionDef} of the stub."""
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    return {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}


def test_the_stub_docstrings_are_the_packages():
    """The stub carries the docstrings ``help()`` shows, physical entries
    filled in as the package fills them at import."""
    stub = _stub_functions()
    documented = [n for n, f in stub.items() if ast.get_docstring(f) is not None]
    assert set(FUNCTIONS + ["photon_rate", "score", "claims"]) <= set(documented)
    for name in documented:
        assert ast.get_docstring(stub[name]) == inspect.getdoc(getattr(v2ref, name)), name


def test_the_physical_entries_are_written_once():
    """No docstring in the package's source describes a physical input by
    hand: each entry comes from the declaration (a hand-written copy would
    drift, as the stub's ``photons >= 0`` once did)."""
    source = (ROOT / "python" / "v2ref" / "__init__.py").read_text(encoding="utf-8")
    for p in _v2ref.PHYSICAL_PARAMETERS:
        assert p["what"].split("{")[0] not in source, p["what"]
        assert p["doc"] not in source, p["name"]


def _physical_keywords(name):
    """The physical keyword arguments of ``v2ref.<name>``, in order."""
    sig = inspect.signature(getattr(v2ref, name))
    return [
        k for k in sig.parameters if k in _declaration.DEFAULTS and k not in NOT_PHYSICAL.get(name, ())
    ]


@pytest.mark.parametrize("name", FUNCTIONS)
def test_every_physical_keyword_reaches_the_library(name):
    """Each physical keyword argument is passed on (a wrong type of it is
    refused by its name), not silently dropped."""
    args = (np.ones((2, 16)),) if name == "estimate" else ()
    keywords = _physical_keywords(name)
    assert len(keywords) >= 10, (name, keywords)
    for k in keywords:
        with pytest.raises(TypeError, match=f"^{k}: "):
            getattr(v2ref, name)(*args, **{k: object()})
