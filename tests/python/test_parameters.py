"""The physical inputs are one struct in the library
(``v2ref_commands::parameters::Physical``, serde) with a table of their
help texts (``PARAMETERS``). The package's signatures are kept by hand and
checked here against the built library's defaults and the CLI's flags; the
docstring entries are filled from the library's table at import; the stub
is generated from the source (``python3 scripts/stub.py``). These tests
also check that each keyword reaches the library.
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
from conftest import release_binary
from v2ref import _v2ref

ROOT = Path(__file__).resolve().parents[2]
STUB = ROOT / "python" / "v2ref" / "__init__.pyi"

# The public functions that take physical keyword arguments.
FUNCTIONS = ["estimate", "synthesize", "simulate", "bias", "snr", "piston", "plan"]
# Their keyword arguments named as a physical input that take something
# else: plan's grids, piston's list of frequencies.
NOT_PHYSICAL = {"plan": {"fringe_hz", "stroke_um"}, "piston": {"fringe_hz"}}


@pytest.mark.parametrize("name", FUNCTIONS)
def test_each_physical_keyword_defaults_to_the_librarys(name):
    """The signatures are kept by hand: each physical keyword's default is
    the library's (``Physical::DEFAULT``; a default changed on one side
    fails)."""
    sig = inspect.signature(getattr(v2ref, name))
    for k in _physical_keywords(name):
        assert sig.parameters[k].default == _v2ref.PHYSICAL_DEFAULTS[k], (name, k)
    assert list(_v2ref.PHYSICAL_DEFAULTS) == list(_v2ref.PHYSICAL_KEYWORDS)
    assert len(_v2ref.PHYSICAL_DEFAULTS) == 27


COMMANDS = {"synthesize": "synth"}
# The CLI's flags a function does without: estimate's N is the array's width.
CLI_ONLY = {"estimate": {"samples", "stroke_um"}}


@pytest.mark.needs_bin
@pytest.mark.parametrize("name", FUNCTIONS)
def test_each_function_takes_its_commands_physical_flags(name):
    """Each function's physical keywords are the physical flags of its CLI
    command (``--no-photon-noise`` as ``photon_noise``): a keyword missing
    on one side fails."""
    command = COMMANDS.get(name, name)
    help_text = subprocess.run(
        [str(release_binary()), command, "--help"], capture_output=True, text=True, check=True
    ).stdout
    flags = {w.split("=")[0].rstrip(",") for w in help_text.split() if w.startswith("--")}
    names = {f[2:].replace("-", "_").removeprefix("no_") for f in flags}
    physical = set(_v2ref.PHYSICAL_KEYWORDS) - NOT_PHYSICAL.get(name, set()) - CLI_ONLY.get(name, set())
    assert names & physical == set(_physical_keywords(name)), name


def test_an_unknown_physical_name_offers_the_nearest():
    """A name that is no physical input reaching the library is refused
    with a TypeError offering the nearest; a wrong type names its keyword."""
    with pytest.raises(TypeError, match="did you mean 'wavelength_um'"):
        _v2ref.bias({"wavelenth_um": 2.0}, "positive", False)
    with pytest.raises(TypeError, match="^samples: "):
        _v2ref.bias({"samples": 1.5}, "positive", False)


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
        ("_oracle.py", "    rows: int = 1000,", "    rows: int = 1001,"),
        ("_oracle.py", "Number of rows (scans)", "Number of rows"),
        ("_docstrings.py", 'f"{kind}, default {default!r}"', 'f"{kind}, defaults to {default!r}"'),
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
    source = "".join(f.read_text(encoding="utf-8") for f in (ROOT / "python" / "v2ref").glob("*.py"))
    for p in _v2ref.PHYSICAL_PARAMETERS:
        assert p["what"].split("{")[0] not in source, p["what"]
        assert p["doc"] not in source, p["name"]


def _physical_keywords(name):
    """The physical keyword arguments of ``v2ref.<name>``, in order."""
    sig = inspect.signature(getattr(v2ref, name))
    return [
        k for k in sig.parameters if k in _v2ref.PHYSICAL_DEFAULTS and k not in NOT_PHYSICAL.get(name, ())
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
