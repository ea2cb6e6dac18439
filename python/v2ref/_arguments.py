"""The keyword arguments' checks, shared by the package's functions (the
Rust side checks every value; these check types and convert): integers,
numbers (one, or a sequence where a keyword takes several), flags and
words; paths as UTF-8 text; arrays as C-contiguous
float64 (no copy when they are one); the physical keyword arguments and
their docstring entries; a sidecar given as a dict or a path.
"""

import collections.abc as _abc
import inspect as _inspect
import os as _os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _docstrings, _v2ref

#: The physical inputs as the library states them (``Physical::DEFAULT``,
#: also the CLI's defaults, and the help text of each).
_declaration = _docstrings.declaration(_v2ref)
_DEFAULTS: Dict[str, Any] = _declaration.DEFAULTS

_PathLike = Union[str, _os.PathLike[str]]


def _uint(name: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
        raise TypeError(f"{name}: {value!r} is not an integer; accepted: an integer from 0 to 2^64 - 1")
    if value < 0 or value >= 2**64:
        raise ValueError(f"{name}: {value} is out of range; accepted: an integer from 0 to 2^64 - 1")
    return int(value)


def _to_float(name: str, value: Any) -> float:
    """``float(value)``, an integer too large for a float refused by name."""
    try:
        return float(value)
    except OverflowError:
        raise ValueError(
            f"{name}: {value} is out of range; accepted: a number within ±1.8e308"
        ) from None


def _is_number(value: Any) -> bool:
    """An int or float (Python's or NumPy's) but not a bool: a flag is not a number."""
    return not isinstance(value, (bool, _np.bool_)) and isinstance(
        value, (int, float, _np.integer, _np.floating)
    )


def _float(name: str, value: Any) -> float:
    """A number keyword as a float; anything else (a str, a bool, None, an
    array) refused naming the keyword: the one check of every number."""
    if not _is_number(value):
        raise TypeError(f"{name}: {value!r} is not a real number; accepted: an int or a float")
    return _to_float(name, value)


def _numbers(name: str, value: Any, accepted: str) -> List[float]:
    """A keyword taking a number or a sequence of numbers (a list, tuple,
    range or 1-D array) as a list of floats, each element checked by
    :func:`_float`. A string is refused, never read one character a
    number; so is anything else, naming the keyword and ``accepted``."""
    if _is_number(value):
        return [_float(name, value)]
    if isinstance(value, _np.ndarray) and value.ndim == 1:
        value = list(value)
    if isinstance(value, (str, bytes, bytearray)) or not isinstance(value, _abc.Sequence):
        raise TypeError(f"{name}: {value!r} is not a number or a sequence of numbers; accepted: {accepted}")
    return [_float(f"{name}[{i}]", v) for i, v in enumerate(value)]


def _grid(name: str, value: Any, unit: str) -> List[float]:
    """A grid keyword (``plan``'s ``fringe_hz``, ``stroke_um``; ``piston``'s
    ``fringe_hz``): None is the default, an empty list."""
    if value is None:
        return []
    accepted = (
        f"a number ({unit}) or a list, tuple, range or 1-D array of them; for the CLI's "
        "A:B:N give numpy.linspace(A, B, N), for A:B:N:log numpy.geomspace(A, B, N)"
    )
    return _numbers(name, value, accepted)


def _count(name: str, value: Any, least: int) -> int:
    """An integer keyword of ``least`` or more (a bool is not a count)."""
    n = _uint(name, value)
    if n < least:
        raise ValueError(f"{name}: {n} is out of range; accepted: an integer of {least} or more")
    return n


def _flag(name: str, value: Any) -> bool:
    if not isinstance(value, (bool, _np.bool_)):
        raise TypeError(f"{name}: {value!r} is not a bool")
    return bool(value)


def _not_masked(name: str, x: Any) -> None:
    """Refuses a masked array: its masked values would be used as numbers."""
    if isinstance(x, _np.ma.MaskedArray):
        raise TypeError(
            f"{name}: a masked array; its masked values would be used as numbers. "
            "Pass the rows to keep (x[~x.mask.any(axis=1)] for a 2-D array, x.compressed() "
            "for a 1-D one) or filled values (x.filled(v))"
        )


def _word(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{name}: {value!r} is not a string")
    return value


def _physical(values: Mapping[str, Any], exclude: Sequence[str] = ()) -> Dict[str, Any]:
    """The physical keyword arguments among ``values`` (but ``exclude``), types checked, paths as strings."""
    out: Dict[str, Any] = {}
    for k, v in values.items():
        if k not in _DEFAULTS or k in exclude or v is None:
            continue
        kind = _declaration.KINDS[k]
        if kind == "path":
            if not isinstance(v, (str, bytes, _os.PathLike)):
                raise TypeError(f"{k}: {v!r} is not a path")
            v = _utf8_path(k, v)
        elif kind == "word":
            v = _word(k, v)
        elif kind == "int":
            v = _uint(k, v)
        elif kind == "bool":
            v = _flag(k, v)
        else:
            v = _float(k, v)
        out[k] = v
    return out


def _documented(*, exclude: Sequence[str] = ()):
    """Fills the ``{physical}`` line of a function's docstring with an entry
    per physical keyword argument of its signature (but ``exclude``), written
    once in the library's declaration (``_docstrings.fill``)."""

    def fill(f):
        keywords = [k for k in _inspect.signature(f).parameters if k not in exclude]
        f.__doc__ = _docstrings.fill(_declaration, f.__doc__, keywords)
        return f

    return fill


#: Largest copy a conversion makes, bytes (half the physical memory where
#: it can be read, else 4 GiB): an array that would need more (a
#: broadcast view claiming 10^9 rows, a non-float64 array of hundreds of
#: GiB) is refused by name before NumPy tries. A C-contiguous float64
#: array is used in place, without a copy, whatever its size.
def _copy_limit() -> int:
    try:
        return _os.sysconf("SC_PHYS_PAGES") * _os.sysconf("SC_PAGE_SIZE") // 2
    except (AttributeError, ValueError, OSError):
        return 4 << 30


def _contiguous(name: str, a: _np.ndarray, shape_words: str) -> _np.ndarray:
    """``a`` as C-contiguous float64, refusing a copy beyond :func:`_copy_limit`."""
    if a.dtype == _np.float64 and a.flags.c_contiguous:
        return a
    need = int(a.size) * 8
    limit = _copy_limit()
    if need > limit:
        raise ValueError(
            f"{name}: shape {a.shape} (strides {a.strides}, dtype {a.dtype}) would need a "
            f"{need / 2**30:.3g} GiB float64 copy, over the {limit / 2**30:.3g} GiB allowed; "
            f"pass {shape_words} as a C-contiguous float64 array (numpy.ascontiguousarray(x, dtype='<f8')), "
            "which is used without a copy"
        )
    return _np.ascontiguousarray(a, dtype=_np.float64)


def _matrix(name: str, x: Any) -> _np.ndarray:
    """A 2-D C-contiguous float64 view of ``x`` (no copy when it is one)."""
    _not_masked(name, x)
    a = _np.asarray(x)
    if a.dtype == _np.bool_ or not (
        _np.issubdtype(a.dtype, _np.floating) or _np.issubdtype(a.dtype, _np.integer)
    ):
        raise TypeError(
            f"{name}: dtype {a.dtype} is not a real number type; a 2-D float64 array (rows, samples) is needed"
        )
    if a.ndim != 2:
        raise TypeError(
            f"{name}: {a.ndim}-D array of shape {a.shape}; a 2-D array (rows, samples) is needed"
        )
    return _contiguous(name, a, "a 2-D array (rows, samples)")


def _channel_rows(name: str, x: Any) -> Tuple[_np.ndarray, Optional[int]]:
    """Rows of a wide-band set, (rows, N), or of a dispersed one, (rows, C,
    N), as a 2-D C-contiguous float64 view (rows, C·N) and C (None for a
    2-D array); no copy when ``x`` is C-contiguous float64."""
    _not_masked(name, x)
    a = _np.asarray(x)
    if a.ndim not in (2, 3):
        raise TypeError(
            f"{name}: {a.ndim}-D array of shape {a.shape}; a 2-D array (rows, N), "
            "or a 3-D array (rows, C, N) for a dispersed set, is needed"
        )
    if a.ndim == 2:
        return _matrix(name, a), None
    if a.dtype == _np.bool_ or not (
        _np.issubdtype(a.dtype, _np.floating) or _np.issubdtype(a.dtype, _np.integer)
    ):
        raise TypeError(
            f"{name}: dtype {a.dtype} is not a real number type; a float64 array (rows, C, N) is needed"
        )
    if 0 in a.shape:
        raise ValueError(
            f"{name}: empty array of shape {a.shape}; an array (rows, C, N) with at least one row, channel and sample is needed"
        )
    a = _contiguous(name, a, "an array (rows, C, N)")
    return a.reshape(a.shape[0], a.shape[1] * a.shape[2]), int(a.shape[1])


def _vector(name: str, x: Any) -> _np.ndarray:
    _not_masked(name, x)
    a = _np.asarray(x)
    if a.dtype == _np.bool_ or not (
        _np.issubdtype(a.dtype, _np.floating) or _np.issubdtype(a.dtype, _np.integer)
    ):
        raise TypeError(f"{name}: dtype {a.dtype} is not a real number type")
    if a.ndim != 1:
        raise TypeError(f"{name}: {a.ndim}-D array of shape {a.shape}; a 1-D array (one value per row) is needed")
    return _contiguous(name, a, "a 1-D array (one value per row)")


def _utf8_path(name: str, value: Any) -> str:
    """The path `value` (str, bytes, os.PathLike) as text for the readers
    that take one: a path whose bytes are not UTF-8 is refused naming the
    keyword (the extension takes text paths), not left to a codec error."""
    path = _os.fsdecode(value)
    try:
        path.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError(
            f"{name}: {value!r} is not a UTF-8 path; this keyword takes a path of UTF-8 text (rename the file)"
        ) from None
    return path


def _sidecar_arg(sidecar: Any) -> Tuple[Any, str]:
    """(the sidecar as the extension takes it, name for messages) of a
    sidecar given as a dict (passed as a dict) or a path (the file's text)."""
    if isinstance(sidecar, _abc.Mapping):
        return dict(sidecar), "<dict>"
    if isinstance(sidecar, (str, bytes, _os.PathLike)):
        path = _os.fsdecode(sidecar)
        # The name in messages: bytes that are not UTF-8 as U+FFFD.
        name = path.encode("utf-8", "surrogateescape").decode("utf-8", "replace")
        # Read by the extension as the CLI reads it: a FIFO refused without
        # waiting, a regular file only, at most 16 MiB.
        return _v2ref._read_sidecar(path), name
    raise TypeError(
        f"sidecar: {type(sidecar).__name__} is not a sidecar; give the dict returned by synthesize() or the path of a SET.json"
    )
