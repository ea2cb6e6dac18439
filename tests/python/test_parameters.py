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

import numpy as np
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
# Their keyword arguments named as a physical input that take something
# else: plan's grids, piston's list of frequencies.
NOT_PHYSICAL = {"plan": {"fringe_hz", "stroke_um"}, "piston": {"fringe_hz"}}
STUB = ROOT / "python" / "v2ref" / "__init__.pyi"


def test_the_declaration_is_complete():
    assert list(TABLE) == list(DEFAULTS) == list(_v2ref.PHYSICAL_KEYWORDS)
    assert len(TABLE) == 24
    for p in TABLE.values():
        assert p["accepted"], p


def _mismatched_defaults(defaults):
    """The physical keywords of ``defaults`` whose default is not the declared one."""
    return [k for k, v in defaults.items() if k in DEFAULTS and v != DEFAULTS[k]]


def _signature_defaults(name):
    """{physical keyword: default} of ``v2ref.<name>``'s signature."""
    sig = inspect.signature(getattr(v2ref, name))
    return {k: p.default for k, p in sig.parameters.items() if k in DEFAULTS}


def _stub_defaults():
    """{function: {keyword: default}} of python/v2ref/__init__.pyi."""
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
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
def test_signature_defaults_are_the_declared_ones(name):
    physical = _signature_defaults(name)
    assert len(physical) >= 10, (name, physical)
    assert _mismatched_defaults(physical) == [], name


@pytest.mark.parametrize("name", FUNCTIONS)
def test_stub_defaults_are_the_declared_ones(name):
    stub = {k: v for k, v in _stub_defaults()[name].items() if k in DEFAULTS}
    assert len(stub) >= 10, (name, stub)
    assert _mismatched_defaults(stub) == [], name


@pytest.mark.parametrize("name", FUNCTIONS)
def test_a_changed_default_would_be_seen(name):
    """The power of the two tests above, on the real signature and stub: a
    default planted 2 % off (or flipped, for a switch) is the one mismatch
    found."""
    for where, defaults in [("signature", _signature_defaults(name)),
                            ("stub", _stub_defaults()[name])]:
        for k, v in defaults.items():
            if k not in DEFAULTS or v is None or isinstance(v, str):
                continue
            planted = (not v) if isinstance(v, bool) else v * 1.02 if v else 1
            assert _mismatched_defaults({**defaults, k: planted}) == [k], (name, where, k)


@pytest.mark.needs_bin
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


def _stub_functions():
    """{name: ast.FunctionDef} of the stub."""
    tree = ast.parse(STUB.read_text(encoding="utf-8"))
    return {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}


def _physical_keywords(name):
    """The physical keyword arguments of ``v2ref.<name>``, in order."""
    sig = inspect.signature(getattr(v2ref, name))
    return [k for k in sig.parameters if k in TABLE and k not in NOT_PHYSICAL.get(name, ())]


def _entry(doc, keyword):
    """The docstring entry of ``keyword``: its head line and its text on one line."""
    lines = doc.splitlines()
    heads = [i for i, l in enumerate(lines) if re.match(rf"{keyword} : ", l)]
    assert len(heads) == 1, (keyword, heads)
    i = heads[0]
    body = []
    for line in lines[i + 1 :]:
        if not line.startswith("    "):
            break
        body.append(line.strip())
    return lines[i], " ".join(body)


@pytest.mark.parametrize("where", ["package", "stub"])
@pytest.mark.parametrize("name", FUNCTIONS + ["photon_rate"])
def test_docstrings_state_each_declaration(name, where):
    """Each physical keyword argument's entry, in ``help()`` and in the stub,
    is the declaration's: its help text (unit and accepted range included)
    and its default (or what leaving it unset means)."""
    if where == "package":
        doc = inspect.getdoc(getattr(v2ref, name))
    else:
        doc = ast.get_docstring(_stub_functions()[name])
    sig = inspect.signature(getattr(v2ref, name))
    keywords = _physical_keywords(name)
    assert keywords, name
    for k in keywords:
        head, text = _entry(doc, k)
        p = TABLE[k]
        want = " ".join(p["doc"].split())
        assert text.startswith(want), (name, k, text, want)
        assert f", {p['unit']}: " in want or not p["unit"], (k, want)
        assert p["accepted"] in want or p["accepted"] == "true or false", (k, want)
        default = sig.parameters[k].default
        if default is None:
            assert head.endswith(", optional"), (name, head)
            assert text.endswith(f"Default: {' '.join(p['unset_doc'].split())}."), (name, k, text)
        else:
            assert head.endswith(f", default {default!r}"), (name, head)


def test_the_physical_entries_are_written_once():
    """No docstring in the package's source describes a physical input by
    hand: each entry comes from the declaration (a hand-written copy would
    drift, as the stub's ``photons >= 0`` once did)."""
    source = (ROOT / "python" / "v2ref" / "__init__.py").read_text(encoding="utf-8")
    for p in TABLE.values():
        assert p["what"].split("{")[0] not in source, p["what"]
        assert p["doc"] not in source, p["name"]


def test_the_stub_docstrings_are_the_packages():
    """The stub carries the docstrings the package builds at import (editors
    read the stub); ``python scripts/stub_docstrings.py`` rewrites them."""
    stub = _stub_functions()
    documented = [n for n, f in stub.items() if ast.get_docstring(f) is not None]
    assert set(FUNCTIONS + ["photon_rate", "score", "claims"]) <= set(documented)
    for name in documented:
        got = ast.get_docstring(stub[name])
        assert got == inspect.getdoc(getattr(v2ref, name)), (
            f"{name}: the stub's docstring is out of date: run python scripts/stub_docstrings.py"
        )


def test_the_stub_signatures_are_the_packages():
    """The stub's hand-written signatures have the package's parameters, in
    the same order, of the same kind, with the same defaults."""
    for name, node in _stub_functions().items():
        sig = inspect.signature(getattr(v2ref, name))
        a = node.args
        stub = [(x.arg, "POSITIONAL_OR_KEYWORD") for x in a.posonlyargs + a.args]
        stub += [(x.arg, "KEYWORD_ONLY") for x in a.kwonlyargs]
        got = [(p.name, p.kind.name) for p in sig.parameters.values()]
        assert stub == got, name
        defaults = dict(zip([x.arg for x in a.args][len(a.args) - len(a.defaults) :], a.defaults))
        defaults.update({x.arg: d for x, d in zip(a.kwonlyargs, a.kw_defaults) if d is not None})
        for k, d in defaults.items():
            if isinstance(d, ast.Constant) and d.value is Ellipsis:
                continue
            assert ast.literal_eval(d) == sig.parameters[k].default, (name, k)


@pytest.mark.parametrize("name", FUNCTIONS)
def test_every_physical_keyword_reaches_the_library(name):
    """Each physical keyword argument is passed on (a wrong type of it is
    refused by its name), not silently dropped."""
    args = (np.ones((2, 16)),) if name == "estimate" else ()
    for k in _physical_keywords(name):
        with pytest.raises(TypeError, match=f"^{k}: "):
            getattr(v2ref, name)(*args, **{k: object()})


def test_every_declared_input_is_a_keyword_argument():
    """A declared input missing from every signature is seen (the
    signatures are written by hand)."""
    used = set()
    for name in FUNCTIONS:
        used |= set(_physical_keywords(name))
    assert used == set(TABLE)
