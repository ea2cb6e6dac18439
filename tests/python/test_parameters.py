"""The physical inputs are declared once, in the library
(``v2ref::parameters``): their names, defaults, units and ranges. The
Python signatures stay explicit (for editors and ``help()``); these tests
check that every signature, the stub and the CLI's ``--help`` agree with
the one declaration, so that a parameter added or changed in one place and
not the others fails here.
"""

from __future__ import annotations

import ast
import inspect
import json
import os
import re
import subprocess
from pathlib import Path

import pytest

import v2ref
from v2ref import _v2ref

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("V2REF_BIN", ROOT / "target" / "release" / "v2ref"))
if not BIN.is_absolute():
    BIN = ROOT / BIN

DEFAULTS = json.loads(_v2ref.PHYSICAL_DEFAULTS)
TABLE = {p["name"]: p for p in json.loads(_v2ref.PHYSICAL_PARAMETERS)}

# The public functions that take physical keyword arguments.
FUNCTIONS = ["estimate", "synthesize", "simulate", "bias", "snr", "piston", "plan"]


def test_the_declaration_is_complete():
    assert list(TABLE) == list(DEFAULTS) == list(_v2ref.PHYSICAL_KEYWORDS)
    assert len(TABLE) == 24
    for p in TABLE.values():
        assert p["accepted"], p


@pytest.mark.parametrize("name", FUNCTIONS)
def test_signature_defaults_are_the_declared_ones(name):
    sig = inspect.signature(getattr(v2ref, name))
    physical = [k for k in sig.parameters if k in DEFAULTS]
    assert len(physical) >= 10, (name, physical)
    for k in physical:
        assert sig.parameters[k].default == DEFAULTS[k], (name, k)


def _stub_defaults():
    """{function: {keyword: default}} of python/v2ref/__init__.pyi."""
    tree = ast.parse((ROOT / "python" / "v2ref" / "__init__.pyi").read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            args = node.args
            out[node.name] = {
                a.arg: ast.literal_eval(d)
                for a, d in zip(args.kwonlyargs, args.kw_defaults)
                if d is not None
            }
    return out


@pytest.mark.parametrize("name", FUNCTIONS)
def test_stub_defaults_are_the_declared_ones(name):
    stub = _stub_defaults()[name]
    physical = [k for k in stub if k in DEFAULTS]
    assert len(physical) >= 10, (name, physical)
    for k in physical:
        assert stub[k] == DEFAULTS[k], (name, k)


def test_a_changed_default_would_be_seen():
    # The power of the two tests above: a default off by a little differs.
    assert DEFAULTS["wavelength_um"] != 2.2 * 1.02
    assert inspect.signature(v2ref.bias).parameters["wavelength_um"].default == 2.2


@pytest.mark.skipif(not BIN.exists(), reason=f"no v2ref binary at {BIN}")
@pytest.mark.parametrize("command", ["simulate", "synth"])
def test_cli_help_states_each_declared_default(command):
    text = subprocess.run(
        [str(BIN), command, "--help"], capture_output=True, text=True, check=True
    ).stdout
    # One entry per flag: the lines from its name to the next flag's.
    entries = {}
    for chunk in re.split(r"\n\s+(?=--[a-z])", text):
        m = re.match(r"(--[a-z-]+)", chunk)
        if m:
            entries[m.group(1)] = " ".join(chunk.split())
    for k, v in DEFAULTS.items():
        if v is None or isinstance(v, bool) or k == "spectrum_csv":
            continue
        flag = "--" + k.replace("_", "-")
        assert flag in entries, (command, flag)
        shown = f"{v:g}" if isinstance(v, float) else str(v)
        assert f"[default: {shown}]" in entries[flag], (command, flag, entries[flag])
