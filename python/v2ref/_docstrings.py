"""The docstring entries of the physical keyword arguments, written from
the library's table of them (``_v2ref.PHYSICAL_PARAMETERS`` and
``PHYSICAL_DEFAULTS``, read by :func:`declaration`): the package fills
them in at import and ``scripts/stub.py`` into the stub, so that
``help()`` and editors read the same text.
"""

import textwrap
import types


def declaration(library):
    """The physical inputs as the built ``library`` (``v2ref._v2ref``)
    states them: ``DEFAULTS`` (None: unset), ``KINDS`` (float, int, bool,
    word or path, from the default's type), ``DOCS`` and ``UNSET_DOCS``."""
    defaults = dict(library.PHYSICAL_DEFAULTS)
    kind_of_type = {bool: "bool", int: "int", str: "word", float: "float"}
    # Unset by default, so their kind is not the default's type.
    declared = {"spectrum_csv": "path", "channels_csv": "path", "channels": "int"}
    kinds = {k: declared.get(k) or kind_of_type.get(type(v), "float") for k, v in defaults.items()}
    table = library.PHYSICAL_PARAMETERS
    return types.SimpleNamespace(
        DEFAULTS=defaults,
        KINDS=kinds,
        DOCS={p["name"]: p["doc"] for p in table},
        UNSET_DOCS={p["name"]: p["unset_doc"] for p in table},
    )

#: The type a docstring entry states for each kind of input.
_TYPE_WORDS = {"float": "float", "int": "int", "bool": "bool", "word": "str", "path": "path"}


def entry(declaration, name: str, indent: str) -> str:
    """The entry of the input ``name``: type, default (or what leaving it
    unset means) and help text, wrapped at 76 columns."""
    kind = _TYPE_WORDS[declaration.KINDS[name]]
    default = declaration.DEFAULTS[name]
    doc = declaration.DOCS[name]
    if default is None:
        head, text = f"{kind}, optional", f"{doc} Default: {declaration.UNSET_DOCS[name]}."
    else:
        head, text = f"{kind}, default {default!r}", doc
    body = textwrap.fill(text, 76, initial_indent=indent + "    ", subsequent_indent=indent + "    ")
    return f"{indent}{name} : {head}\n{body}"


def fill(declaration, doc: str, keywords) -> str:
    """``doc`` with its ``{physical}`` line replaced by the entry of each of
    ``keywords`` (a signature's, in order) that is a physical input."""
    lines = doc.split("\n")
    at = [line.strip() for line in lines].index("{physical}")
    indent = lines[at][: len(lines[at]) - len(lines[at].lstrip())]
    entries = [entry(declaration, k, indent) for k in keywords if k in declaration.DEFAULTS]
    return "\n".join(lines[:at] + entries + lines[at + 1 :])
