"""Writes python/v2ref/__init__.pyi, the package's stub, from its source.

Each public function (named in ``__all__`` of ``python/v2ref/__init__.py``)
of the package's modules listed in ``MODULES`` gets its signature as
written in the source and the docstring ``help()`` shows: the physical
keyword arguments' entries are filled in from the built library's table
(``v2ref._v2ref.PHYSICAL_PARAMETERS``) as the package does at import
(``_docstrings.fill``): run it with the built package importable
(``python3 scripts/stub.py``); ``--check`` exits 1
(printing a diff) when the stub is not what the source makes, as
``tests/python/test_parameters.py`` does.
"""

import ast
import difflib
import importlib.util
import inspect
import pathlib
import sys

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "python" / "v2ref"
STUB = PACKAGE / "__init__.pyi"

#: The package's modules that define its public functions, in the stub's
#: order (the order of ``__all__``; OIFITS's last, in its own order).
MODULES = ("_oracle.py", "_budget.py", "_plan.py", "__init__.py", "oifits.py")

HEADER = '''"""Type stubs of the v2ref package (units in every parameter description).

Generated from the package's source by scripts/stub.py: do not edit.
"""

import os as _os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

_PathLike = Union[str, _os.PathLike[str]]

__version__: str
ESTIMATE_COLUMNS: Tuple[str, ...]
'''


def load(name):
    """The module ``PACKAGE/name.py``, loaded by path (not through the package)."""
    spec = importlib.util.spec_from_file_location(name, PACKAGE / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def exclusions(tree, node):
    """The names ``@_documented(exclude=...)`` leaves out of ``node``'s entries."""
    constants = {
        t.id: s.value
        for s in tree.body
        if isinstance(s, ast.Assign)
        for t in s.targets
        if isinstance(t, ast.Name)
    }
    for d in node.decorator_list:
        if isinstance(d, ast.Call) and getattr(d.func, "id", None) == "_documented":
            for k in d.keywords:
                value = constants.get(getattr(k.value, "id", None), k.value)
                return set(ast.literal_eval(value))
            return set()
    return None


def docstring(text):
    """A docstring's lines in the stub, indented as a function body."""
    lines = text.split("\n")
    return ['    """' + lines[0]] + [("    " + l).rstrip() for l in lines[1:]] + ['    """']


def appended_docs(tree):
    """What the module appends to its functions' docstrings, by function:
    ``f.__doc__ = (f.__doc__ or "") + TEXT`` with ``TEXT`` a module-level
    string (one text shared by several functions, written once)."""
    texts = {
        s.targets[0].id: s.value.value
        for s in tree.body
        if isinstance(s, ast.Assign)
        and isinstance(s.targets[0], ast.Name)
        and isinstance(s.value, ast.Constant)
        and isinstance(s.value.value, str)
    }
    out = {}
    for s in tree.body:
        target = s.targets[0] if isinstance(s, ast.Assign) else None
        if not (isinstance(target, ast.Attribute) and target.attr == "__doc__"):
            continue
        if isinstance(s.value, ast.BinOp) and isinstance(s.value.right, ast.Name):
            out[target.value.id] = texts[s.value.right.id]
    return out


def functions(path, public, declaration, docstrings):
    """The stub's lines of each function of ``path`` named in ``public``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    appended = appended_docs(tree)
    out = []
    for node in tree.body:
        if not isinstance(node, ast.FunctionDef) or node.name not in public:
            continue
        returns = f" -> {ast.unparse(node.returns)}" if node.returns else ""
        out += ["", f"def {node.name}({ast.unparse(node.args)}){returns}:"]
        doc = ast.get_docstring(node, clean=False)
        if doc is not None and node.name in appended:
            doc += appended[node.name]
        if doc is None:
            out[-1] += " ..."
            continue
        excluded = exclusions(tree, node)
        if excluded is not None:
            a = node.args
            keywords = [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs]
            doc = docstrings.fill(declaration, doc, [k for k in keywords if k not in excluded])
        out += docstring(inspect.cleandoc(doc))
    return out


def public_names():
    """``__all__`` of the package: its list, and the names added to it."""
    tree = ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8"))
    names = []
    for s in tree.body:
        target = getattr(s, "target", None) or (getattr(s, "targets", None) or [None])[0]
        if getattr(target, "id", None) == "__all__":
            names += ast.literal_eval(s.value)
    return set(names)


def stub():
    """The stub's text."""
    docstrings = load("_docstrings")
    declaration = docstrings.declaration(importlib.import_module("v2ref._v2ref"))
    public = public_names()
    lines = HEADER.rstrip("\n").split("\n")
    for name in MODULES:
        lines += functions(PACKAGE / name, public, declaration, docstrings)
    defined = {line[4 : line.index("(")] for line in lines if line.startswith("def ")}
    left = sorted(public - defined - {"ESTIMATE_COLUMNS"})  # (declared in HEADER)
    if left:
        sys.exit(f"scripts/stub.py: {', '.join(left)} of __all__ defined in none of MODULES")
    return "\n".join(lines) + "\n"


def main():
    want = stub()
    if sys.argv[1:] == ["--check"]:
        now = STUB.read_text(encoding="utf-8")
        if now != want:
            sys.stdout.writelines(
                difflib.unified_diff(now.splitlines(True), want.splitlines(True), str(STUB), "made")
            )
            print(f"{STUB} is out of date: run python3 scripts/stub.py", file=sys.stderr)
            sys.exit(1)
        return
    STUB.write_text(want, encoding="utf-8")
    print(f"{STUB}: written")


if __name__ == "__main__":
    main()
