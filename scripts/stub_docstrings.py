"""Rewrites the docstrings of python/v2ref/__init__.pyi with the package's.

The package fills each function's physical keyword arguments into its
docstring at import, from the library's one declaration
(``v2ref::parameters::PARAMETERS``); editors read the stub instead, so the
stub carries the same text. Run this after changing a docstring or a
parameter (with the package installed: ``pip install .``);
``tests/python/test_parameters.py`` fails while the stub is out of date.
The signatures in the stub are written by hand and checked by that test.
"""

import ast
import inspect
import pathlib

import v2ref

STUB = pathlib.Path(__file__).resolve().parents[1] / "python" / "v2ref" / "__init__.pyi"


def docstring_lines(text):
    """The lines of a function's docstring in the stub, indented."""
    lines = text.split("\n")
    return ['    """' + lines[0]] + [("    " + l).rstrip() for l in lines[1:]] + ['    """']


def main():
    lines = STUB.read_text(encoding="utf-8").split("\n")
    edits = []
    for node in ast.parse("\n".join(lines)).body:
        if isinstance(node, ast.FunctionDef) and ast.get_docstring(node) is not None:
            doc = node.body[0]
            text = inspect.getdoc(getattr(v2ref, node.name))
            edits.append((doc.lineno - 1, doc.end_lineno, docstring_lines(text)))
    for start, end, new in reversed(edits):
        lines[start:end] = new
    STUB.write_text("\n".join(lines), encoding="utf-8")
    print(f"{STUB}: {len(edits)} docstrings")


if __name__ == "__main__":
    main()
