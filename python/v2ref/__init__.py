"""v2ref: the Perrin & Ridgway squared-visibility estimators V1² and V2².

Python face of the Rust reference implementation (the ``v2ref`` command-line
tool's library). Every function takes the CLI's flags as keyword arguments
(``--dx-um`` is ``dx_um``), NumPy arrays in and out, and answers with the
same fields as the command's ``--json`` output:

- :func:`estimate`   per-row V1², V2² of a 2-D array of interferograms
- :func:`synthesize` a test set (interferograms + sidecar with the truth)
- :func:`score`      a pipeline's per-row estimates against a set's truth
- :func:`simulate`   end-to-end Monte Carlo of the normalized estimators
- :func:`bias`, :func:`snr`, :func:`piston`, :func:`claims`

Bad input raises ``ValueError`` (``TypeError`` for a wrong type, dtype or
shape) whose message starts with the keyword argument's name, in the CLI's
words. Long calls release the GIL, use ``threads`` worker threads (0: all
cores; the answer does not depend on it) and stop on Ctrl-C. No call
predicts its duration beforehand (no warning is issued before a long run);
the CLI's progress bar shows the time left at the measured rate.

Units: µm for wavelengths, OPDs and spacings (``_um``), nm for the bandwidth,
mas for diameters, m for baselines and apertures, Hz for fringe frequencies,
photons per sample for fluxes and noise.
"""

import collections.abc as _abc
import contextvars as _contextvars
import functools as _functools
import inspect as _inspect
import json as _json
import os as _os

# The names of typing used in the signatures below; deleted at the end of the
# module so that the namespace holds the API only (the signatures keep the
# types themselves: help() shows them).
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _docstrings, _progress, _v2ref

__version__: str = _v2ref.__version__

__all__ = [
    "estimate",
    "synthesize",
    "powered_set",
    "score",
    "simulate",
    "bias",
    "snr",
    "piston",
    "plan",
    "plan_targets",
    "photon_rate",
    "claims",
    "ESTIMATE_COLUMNS",
]

#: The columns of :func:`estimate`'s answer, in the order of ``v2ref estimate``.
ESTIMATE_COLUMNS = tuple(_v2ref.ESTIMATE_COLUMNS)

#: The physical inputs as the library states them (``Physical::DEFAULT``,
#: also the CLI's defaults, and the help text of each).
_declaration = _docstrings.declaration(_v2ref)
_DEFAULTS: Dict[str, Any] = _declaration.DEFAULTS

_PathLike = Union[str, _os.PathLike[str]]


# --------------------------------------------------------------------------
# Argument checks (the Rust side checks every value; these check types).


def _uint(name: str, value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
        raise TypeError(f"{name}: {value!r} is not an integer")
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


def _float(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, _np.integer, _np.floating)):
        raise TypeError(f"{name}: {value!r} is not a number")
    return _to_float(name, value)


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
            if not isinstance(v, (bool, _np.bool_)):
                raise TypeError(f"{k}: {v!r} is not a bool")
            v = bool(v)
        else:
            if isinstance(v, bool) or not isinstance(v, (int, float, _np.integer, _np.floating)):
                raise TypeError(f"{k}: {v!r} is not a real number")
            v = _to_float(k, v)
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
        try:
            with open(path, encoding="utf-8") as f:
                return f.read(), name
        except OSError as e:
            raise OSError(e.errno, f"sidecar: {name}: {e.strerror}") from None
    raise TypeError(
        f"sidecar: {type(sidecar).__name__} is not a sidecar; give the dict returned by synthesize() or the path of a SET.json"
    )


# --------------------------------------------------------------------------
# The functions.

@_documented()
def estimate(
    interferograms: Any,
    *,
    sidecar: Union[Mapping[str, Any], _PathLike, None] = None,
    bins: str = "positive",
    bias: str = "model",
    calibrator: Any = None,
    continuum_subtracted: Optional[bool] = None,
    threads: int = 0,
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    dx_um: float = 0.5,
    integrating: bool = False,
    visibility: float = 1.0,
    photons: float = 10.0,
    read_noise: float = 0.0,
    photon_noise: bool = True,
    fringe_hz: Optional[float] = None,
    wind_mps: float = 10.0,
    seeing_arcsec: float = 1.0,
    seeing_wavelength_um: Optional[float] = None,
    aperture_m: float = 0.45,
    outer_scale_m: Optional[float] = None,
    sub_samples: int = 6,
    reference: str = "mean",
) -> Dict[str, _np.ndarray]:
    """Per-row V1² and V2² (raw, bias, normalized) of a 2-D array, as ``v2ref estimate``.

    Parameters
    ----------
    interferograms : array_like, shape (rows, N)
        One scan per row, columns in the order of the sidecar's
        ``sample_opd_um`` (column 0 at the white-light fringe); photons per
        sample. N is the array's width. A C-contiguous float64 array is used
        without a copy; other real dtypes are converted.
    sidecar : dict or path, optional
        A synth sidecar (the dict from :func:`synthesize` or a SET.json
        path): the configuration comes from it, and the physical keyword
        arguments must be left at their defaults. The rows may be any number
        of rows of the set's N (a subset of the set's rows, one observation
        of ``layout="observation"``, or other rows), as ``v2ref estimate
        --sidecar SET.json --input ROWS`` takes them.
    bins : {"positive", "band", "all"}
        Fourier bins the estimators sum.
    bias : {"model", "counts"}
        Where the photon bias takes the mean counts from: the model's
        noise-free counts, or each row's own counts.
    calibrator : array_like, shape (rows', N), optional
        A calibrator's interferograms (same N and continuum convention): the
        normalization is the mean of their bias-subtracted estimates.
        Default: the configuration's point source, noise-free (``model``).
    continuum_subtracted : bool, optional
        Without ``sidecar``: True (default) when the rows hold
        M_i = I_i − c_i (photons), False when they hold the counts I_i
        (the CLI's ``--counts``).
    threads : int
        Worker threads (0: all cores); the answer does not depend on it.
    {physical}

    Returns
    -------
    dict of str to ndarray, shape (rows,)
        ``v1_sq_raw``, ``v2_sq_raw`` (photons²), ``v1_sq_bias``,
        ``v2_sq_bias`` (photons²), ``v1_sq``, ``v2_sq`` (normalized,
        dimensionless): the columns of ``v2ref estimate``.
    """
    values = dict(locals())
    data = _matrix("interferograms", interferograms)
    bins = _word("bins", bins)
    bias = _word("bias", bias)
    threads = _v2ref.check_threads(_uint("threads", threads))
    cal = None if calibrator is None else _matrix("calibrator", calibrator)
    if continuum_subtracted is not None and not isinstance(continuum_subtracted, (bool, _np.bool_)):
        raise TypeError(f"continuum_subtracted: {continuum_subtracted!r} is not a bool")
    if sidecar is not None:
        given = [k for k, v in values.items() if k in _DEFAULTS and v != _DEFAULTS[k]]
        if given:
            raise ValueError(
                f"{given[0]}: cannot be used with sidecar (the configuration comes from it)"
            )
        text, name = _sidecar_arg(sidecar)
        physical: Dict[str, Any] = {}
    else:
        text, name = None, ""
        physical = _physical(values)
        physical["samples"] = data.shape[1]
    return _v2ref.estimate(
        data,
        physical,
        text,
        name,
        None if continuum_subtracted is None else bool(continuum_subtracted),
        bins,
        bias,
        cal,
        threads,
    )


@_documented()
def synthesize(
    *,
    rows: int = 1000,
    seed: int = 1,
    threads: int = 0,
    reference_blocks: Optional[int] = None,
    keep_continuum: bool = False,
    layout: str = "sequences",
    observations: int = 1,
    dead_time_s: float = 0.0,
    out: Optional[_PathLike] = None,
    force: bool = False,
    client: Any = None,
    checkpoint: Optional[_PathLike] = None,
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    stroke_um: Optional[float] = None,
    dx_um: float = 0.5,
    samples: int = 128,
    integrating: bool = False,
    visibility: float = 1.0,
    photons: float = 10.0,
    read_noise: float = 0.0,
    photon_noise: bool = True,
    fringe_hz: Optional[float] = None,
    wind_mps: float = 10.0,
    seeing_arcsec: float = 1.0,
    seeing_wavelength_um: Optional[float] = None,
    aperture_m: float = 0.45,
    outer_scale_m: Optional[float] = None,
    sub_samples: int = 6,
    reference: str = "mean",
) -> Tuple[_np.ndarray, Dict[str, Any]]:
    """A set of test interferograms and its sidecar with the truth, as ``v2ref synth``.

    The rows are bit-identical to the ``.npy`` that ``v2ref synth`` writes
    with the same flags and ``seed``, whatever ``threads``.

    Parameters
    ----------
    rows : int
        Number of rows (scans), 2 to 2^31 / samples.
    seed : int
        Seed of the set's random draws.
    threads : int
        Worker threads (0: all cores); the set does not depend on it.
    reference_blocks : int, optional
        Blocks of the truth's reference run: 0 (closed forms only) or 8 to
        1000. None (default): 16 with piston (replicates of the set, whose
        spread the score divides by, as Student-t with blocks - 1 degrees
        of freedom), 8 without (pooled independent rows).
    keep_continuum : bool
        Rows hold the counts I_i (photons) instead of M_i = I_i − c_i.
    layout : str
        How the rows lie in time through the piston (with ``fringe_hz``):
        ``"sequences"`` (default) cuts them from up to 16 independent piston
        sequences, scans spread out in each — the statistics of one scan;
        ``"observation"`` cuts them into ``observations`` observations of
        rows/observations consecutive scans — the observation a plan
        recommends, whose mean over n rows scatters as n consecutive scans
        through one atmosphere do; each reads the start of its own piston
        sequence, at least 4 times as long and two correlation times B/v,
        so its drift is kept. The sidecar's ``layout`` records it (its
        ``note`` says how long the sequences were).
    observations : int
        With ``layout="observation"``: independent observations, each its
        own atmosphere keyed by its index (1 to 1e6, dividing ``rows``;
        their piston together within 2^24 samples). 1 otherwise.
    dead_time_s : float
        With ``layout="observation"``: dead time between consecutive scans,
        s (0 to 3.2e7), as ``plan(dead_time_s=...)``. 0 otherwise.
    out : path, optional
        Also write the set as ``v2ref synth --out`` does: OUT.npy and the
        sidecar OUT.json.
    force : bool
        Replace an existing OUT.npy or OUT.json (never a link, folder or
        device).
    {physical}

    client : dask.distributed.Client, optional
        Runs the truth's reference run (most of a set's cost with piston)
        as ranges of work units on this Dask cluster; the rows are made
        here. Same bits as one process (``docs/dask.md``).
    checkpoint : path, optional
        A folder keeping each finished range of the reference run, as
        :func:`simulate`'s.

    Returns
    -------
    (ndarray of shape (rows, N), dict)
        The interferograms (float64, photons per sample) and the sidecar:
        the same JSON document as ``v2ref synth``'s OUT.json, parsed
        (``truth`` holds what each window and bias convention must give;
        ``data.npy`` is the data file's name with ``out``, else empty).
    """
    values = dict(locals())
    physical = _physical(values)
    npy = ""
    if out is not None:
        if not isinstance(out, (str, bytes, _os.PathLike)):
            raise TypeError(f"out: {out!r} is not a path")
        out = _os.fspath(out)
        # The sidecar names the file in text: bytes that are not UTF-8 as
        # U+FFFD, as the CLI writes them (the file itself keeps its bytes).
        npy = _os.fsencode(_os.path.basename(out)).decode("utf-8", "replace") + ".npy"
    size = (
        _uint("rows", rows),
        _uint("seed", seed),
        _v2ref.check_threads(_uint("threads", threads)),
        None if reference_blocks is None else _uint("reference_blocks", reference_blocks),
    )
    timing = (_word("layout", layout), _uint("observations", observations), _float("dead_time_s", dead_time_s))
    truth_partials = None
    if client is not None or checkpoint is not None:
        from . import dask as _dask

        truth_partials = _dask._partials("truth", (physical, *size, *timing), client, checkpoint)[0]
    return _v2ref.synthesize(
        physical,
        *size,
        bool(keep_continuum),
        npy,
        timing[0],
        # The CLI's writers: the set checked and locked, written whole or
        # not at all, an existing file replaced only with force=True.
        None if out is None else _os.fsdecode(out),
        _flag("force", force),
        *timing[1:],
        truth_partials=truth_partials,
    )



def powered_set(name: str, *, client: Any = None, checkpoint: Optional[_PathLike] = None) -> Tuple[_np.ndarray, Dict[str, Any]]:
    """A conformance vector made large enough to catch a 2 % error, as the Rust library's ``oracle::Set::powered``.

    The piston-free golden vector ``name`` (its inputs and seed) with as
    many rows as a score needs to catch a 2 % error of the mean or the
    variance of either estimator, under every window and bias convention
    of its truth, with probability 0.9 (1.4 to 5.3e5 rows; the rows come
    from a pilot truth of 8192 rows, computed here), and its truth from a
    reference run of 8 times the rows.

    Parameters
    ----------
    name : str
        A piston-free vector of ``golden/vectors/`` (``noise_gaussian``,
        ``noise_poisson``, ``noise_both``, ``bandwidth_disk``,
        ``dispersion``, ``short_scan_odd``, ``integrating``); a vector with
        piston is refused (its truth would need replicates of the whole
        set).
    client : dask.distributed.Client, optional
        Runs the truth's reference run (nearly all of the cost) as ranges
        of work units on this Dask cluster; the pilot and the rows are
        made here. Same bits as one process (``docs/dask.md``).
    checkpoint : path-like, optional
        A folder keeping each finished range of the reference run, as
        :func:`simulate`'s; a rerun computes only the ranges it lacks.

    Returns
    -------
    (ndarray of shape (rows, N), dict)
        The rows (float64, continuum subtracted) and the sidecar, as
        :func:`synthesize` returns them (the data file named ``NAME.npy``).
    """
    if not isinstance(name, str):
        raise TypeError(f"name: {name!r} is not a str")
    if client is None and checkpoint is None:
        return _v2ref.powered_set(name)
    from . import dask as _dask

    rows = _v2ref._powered_rows(name)
    partials = _dask._partials("powered", (name, rows, 1 if client is not None else 0), client, checkpoint)[0]
    return _v2ref.powered_set(name, rows, partials)

#: The keys of the mapping :func:`estimate` returns; :func:`score` reads
#: v1_sq and v2_sq and refuses any other key (a misspelt column would
#: otherwise be left out of the verdict without a word).
_ESTIMATE_KEYS = ("v1_sq_raw", "v2_sq_raw", "v1_sq_bias", "v2_sq_bias", "v1_sq", "v2_sq")


def _rows_claimed(a: Any) -> Optional[int]:
    """The rows of an array-like without converting it (None if unknown)."""
    shape = getattr(a, "shape", None)
    if shape is not None and len(shape) >= 1:
        return int(shape[0])
    return None


def _check_rows(estimates: Any, sidecar: Any) -> None:
    """Refuses estimates of another length than the sidecar's rows (a dict,
    or a file's text) before any copy."""
    try:
        doc = _json.loads(sidecar) if isinstance(sidecar, str) else sidecar
        rows = int(doc["data"]["rows"])
    except (ValueError, KeyError, TypeError):
        return  # the sidecar's own check says what is wrong with it
    cols = estimates.values() if isinstance(estimates, _abc.Mapping) else [estimates]
    for c in cols:
        n = _rows_claimed(c)
        if n is not None and n != rows:
            raise ValueError(
                f"estimates: {n} rows; the sidecar's set has {rows} (one estimate per row of the set is needed)"
            )


def _estimate_columns(estimates: Any, columns: Optional[Sequence[str]]):
    """(v1_sq, v2_sq) of the estimates, either None when absent."""
    if isinstance(estimates, _abc.Mapping):
        found = {k: estimates[k] for k in ("v1_sq", "v2_sq") if k in estimates}
        if not found:
            raise ValueError(
                f"estimates: no column named v1_sq or v2_sq (found: {','.join(map(str, estimates))}); one of them is needed"
            )
        unknown = [k for k in estimates if k not in _ESTIMATE_KEYS]
        if unknown:
            raise ValueError(
                f"estimates: unknown key(s) {', '.join(map(repr, unknown))}; accepted keys: "
                f"{', '.join(_ESTIMATE_KEYS)} (v1_sq and v2_sq are scored; keys are case-sensitive)"
            )
        return tuple(
            None if k not in found else _vector(f"estimates[{k!r}]", found[k])
            for k in ("v1_sq", "v2_sq")
        )
    _not_masked("estimates", estimates)
    a = _np.asarray(estimates)
    if a.dtype.names:
        names = a.dtype.names
        if "v1_sq" not in names and "v2_sq" not in names:
            raise ValueError(
                f"estimates: no field named v1_sq or v2_sq (found: {','.join(names)}); one of them is needed"
            )
        return tuple(
            _vector(f"estimates[{k!r}]", a[k]) if k in names else None for k in ("v1_sq", "v2_sq")
        )
    names = list(columns) if columns is not None else ["v1_sq", "v2_sq"]
    if a.ndim == 1:
        a = a[:, None]
    if a.ndim != 2:
        raise TypeError(
            f"estimates: {a.ndim}-D array of shape {a.shape}; a 2-D array (rows, columns) is needed"
        )
    if a.shape[1] != len(names):
        raise ValueError(
            f"estimates: {a.shape[1]} columns; columns names {len(names)} ({','.join(names)}): one name per column is needed"
        )
    if "v1_sq" not in names and "v2_sq" not in names:
        raise ValueError(f"columns: no column named v1_sq or v2_sq ({','.join(names)}); one of them is needed")
    for k in ("v1_sq", "v2_sq"):
        if names.count(k) > 1:
            # As the CLI's --columns: which of the two is scored would be a guess.
            raise ValueError(f"columns: {k} is named twice ({','.join(names)}); name each column once")
    return tuple(
        _vector(f"estimates[{k!r}]", a[:, names.index(k)]) if k in names else None
        for k in ("v1_sq", "v2_sq")
    )


def score(
    estimates: Any,
    sidecar: Union[Mapping[str, Any], _PathLike],
    *,
    bins: str = "positive",
    bias: str = "model",
    alpha: float = 1e-3,
    columns: Optional[Sequence[str]] = None,
) -> Dict[str, Any]:
    """Score a pipeline's per-row estimates against a set's truth, as ``v2ref score --json``.

    Parameters
    ----------
    estimates : dict, structured array, array_like or OIFITS path
        The normalized per-row estimates (dimensionless), one per row of
        the set: a mapping with ``v1_sq`` and/or ``v2_sq`` (as returned by
        :func:`estimate`), a structured array with those fields, or a 2-D
        array whose columns are named by ``columns`` (default
        ``v1_sq,v2_sq``; a 1-D array needs one name); or the path of an
        OIFITS file (``.fits``, ``.oifits``, ``.fit``, each possibly
        ``.gz``), scored as :func:`score_oifits` does.
    sidecar : dict or path
        The set's sidecar (from :func:`synthesize`, or a SET.json path):
        the truth scored against.
    bins : {"positive", "band", "all"}
        Window of bins the estimates sum.
    bias : {"model", "counts"}
        Bias convention the estimates subtract.
    alpha : float
        Family-wise false-alarm rate of the verdict (Bonferroni over the
        tests made), 0 < alpha < 1.
    columns : sequence of str, optional
        Names of a plain array's columns (others than v1_sq, v2_sq ignored).

    Returns
    -------
    dict
        The fields of ``v2ref score --json``: ``sidecar``, ``estimates``,
        ``bins``, ``bias``, ``rows``, ``alpha``, ``tests``, ``z_crit``,
        ``estimators`` (per estimator: mean, expected_mean, stderr_mean_combined
        (the denominator of z_mean), z_mean, var, expected_var,
        stderr_var_combined (the denominator of z_var), z_var,
        minimum detectable biases, pass), ``pass``.
    """
    from .oifits import is_fits_path, score_oifits

    if is_fits_path(estimates) and columns is None:
        # An OIFITS path: read as `v2ref score --estimates FILE.fits`.
        return score_oifits(estimates, sidecar=sidecar, bins=bins, bias=bias, alpha=alpha)
    text, name = _sidecar_arg(sidecar)
    _check_rows(estimates, text)
    v1, v2 = _estimate_columns(estimates, columns)
    if isinstance(alpha, bool) or not isinstance(alpha, (int, float, _np.integer, _np.floating)):
        raise TypeError(f"alpha: {alpha!r} is not a real number")
    return _v2ref.score(
        v1,
        v2,
        text,
        name,
        "<array>",
        _word("bins", bins),
        _word("bias", bias),
        _to_float("alpha", alpha),
    )


@_documented()
def simulate(
    *,
    trials: int = 100000,
    seed: int = 1,
    threads: int = 0,
    bins: str = "positive",
    bias: str = "model",
    formula: str = "exact",
    client: Any = None,
    checkpoint: Optional[_PathLike] = None,
    chunk_units: Optional[int] = None,
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    stroke_um: Optional[float] = None,
    dx_um: float = 0.5,
    samples: int = 128,
    integrating: bool = False,
    visibility: float = 1.0,
    photons: float = 10.0,
    read_noise: float = 0.0,
    photon_noise: bool = True,
    fringe_hz: Optional[float] = None,
    wind_mps: float = 10.0,
    seeing_arcsec: float = 1.0,
    seeing_wavelength_um: Optional[float] = None,
    aperture_m: float = 0.45,
    outer_scale_m: Optional[float] = None,
    sub_samples: int = 6,
    reference: str = "mean",
) -> Dict[str, Any]:
    """End-to-end Monte Carlo of the normalized estimators, as ``v2ref simulate --json``.

    Parameters
    ----------
    trials : int
        Number of noisy interferograms (rows), 4 to 2^40.
    seed : int
        Seed of the generators.
    threads : int
        Worker threads (0: all cores); the answer does not depend on it.
    bins : {"positive", "band", "all"}
        Fourier bins the estimators sum.
    bias : {"model", "counts"}
        Where the photon bias takes the mean counts from.
    formula : {"exact", "published"}
        Formula of the subtracted bias: exact, or as printed in the paper.
    client : distributed.Client, optional
        Runs the work units as tasks on this Dask cluster (``threads`` then
        counts per task, 0 meaning 1); the answer is the same bits
        (``docs/dask.md``).
    checkpoint : path-like, optional
        A folder keeping each finished range of units; a rerun with the
        same arguments computes only the ranges it lacks.
    chunk_units : int, optional
        Work units (8192 rows each) per task (default: about four tasks
        per worker thread, at least ``v2ref.dask.MIN_UNITS_PER_TASK``).
    {physical}

    Returns
    -------
    dict
        ``mean_v1_sq``, ``var_v1_sq``, their standard errors and closed-form
        expectations (None with piston), the same for V2², ``trials``,
        ``seed``, ``piston``, ``piston_effect`` and every input.
    """
    values = dict(locals())
    threads = _uint("threads", threads)
    if client is not None and threads == 0:
        threads = 1
    args = (
        _physical(values),
        _word("bins", bins),
        _word("bias", bias),
        _word("formula", formula),
        _uint("trials", trials),
        _uint("seed", seed),
        _v2ref.check_threads(threads),
    )
    if client is None and checkpoint is None:
        return _v2ref.simulate(*args)
    from . import dask as _dask

    return _dask._run_units("simulate", args, client, checkpoint, chunk_units)[0]


@_documented()
def bias(
    *,
    finite_scan: bool = False,
    bins: str = "positive",
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    stroke_um: Optional[float] = None,
    dx_um: float = 0.5,
    samples: int = 128,
    integrating: bool = False,
) -> Dict[str, Any]:
    """Noise-free wide-band V1 and V2 for one configuration, as ``v2ref bias --json``.

    Parameters
    ----------
    finite_scan : bool
        Also compute the finite-scan estimators from a sampled interferogram
        (implied by ``stroke_um``).
    bins : {"positive", "band", "all"}
        Fourier bins of the finite-scan estimators.
    {physical}

    Returns
    -------
    dict
        ``v_mono``, ``v1``, ``v2``, ``v1_sq``, ``v2_sq``,
        ``spatial_freq_cpas``, ``sigma_eff_per_um`` (µm⁻¹), ``baseline_m``
        and, with a finite scan, ``finite_scan``.
    """
    values = dict(locals())
    if not isinstance(finite_scan, (bool, _np.bool_)):
        raise TypeError(f"finite_scan: {finite_scan!r} is not a bool")
    return _v2ref.bias(_physical(values), _word("bins", bins), bool(finite_scan))


@_documented()
def snr(
    *,
    bins: str = "positive",
    formula: str = "exact",
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    stroke_um: Optional[float] = None,
    dx_um: float = 0.5,
    samples: int = 128,
    integrating: bool = False,
    visibility: float = 1.0,
    photons: float = 10.0,
    read_noise: float = 0.0,
    photon_noise: bool = True,
) -> Dict[str, Any]:
    """Closed-form expectations, variances and SNRs of V1² and V2², as ``v2ref snr --json``.

    Parameters
    ----------
    bins : {"positive", "band", "all"}
        Window of the exact window statistics (``window_exact``).
    formula : {"exact", "published"}
        Formula: exact, or as printed in the paper's Appendix.
    {physical}

    Returns
    -------
    dict
        ``bias_v1_sq``, ``var_v1_sq``, ``snr1``, … (all bins, photons²),
        ``window_factor``, and ``window_exact`` (None above the largest N
        the exact window statistics take).
    """
    values = dict(locals())
    return _v2ref.snr(
        _physical(values),
        _word("bins", bins),
        _word("formula", formula),
    )


@_documented(exclude=("fringe_hz",))
def piston(
    *,
    fringe_hz: Union[float, Sequence[float], None] = None,
    scans: int = 1000,
    seed: int = 1,
    threads: int = 0,
    bins: str = "positive",
    client: Any = None,
    checkpoint: Optional[_PathLike] = None,
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    stroke_um: Optional[float] = None,
    dx_um: float = 0.5,
    samples: int = 128,
    integrating: bool = False,
    wind_mps: float = 10.0,
    seeing_arcsec: float = 1.0,
    seeing_wavelength_um: Optional[float] = None,
    aperture_m: float = 0.45,
    outer_scale_m: Optional[float] = None,
    sub_samples: int = 6,
    reference: str = "mean",
    psd: str = "two-aperture",
    wind_angle_deg: float = 0.0,
) -> Dict[str, Any]:
    """Differential-piston Monte Carlo at one or more fringe frequencies, as ``v2ref piston --json``.

    Parameters
    ----------
    fringe_hz : float or sequence of float, optional
        Fringe frequencies f = v/λ0, Hz (default: 300 and 1000).
    scans : int
        Consecutive scans per fringe frequency, >= 2.
    seed : int
        Seed (each frequency's seed derives from it and the frequency).
    threads : int
        Worker threads (0: all cores); the answer does not depend on it.
    bins : {"positive", "band", "all"}
        Fourier bins the estimators sum.
    client : distributed.Client, optional
        Runs each fringe frequency as a task on this Dask cluster
        (``threads`` then counts per task, 0 meaning 1); the answer is the
        same bits (``docs/dask.md``).
    checkpoint : path-like, optional
        A folder keeping each finished frequency; a rerun with the same
        arguments computes only those it lacks.
    {physical}
    psd : {"two-aperture", "three-slope"}
        The differential-piston spectrum the sequences are drawn from: the
        two-aperture integral, or the three-slope model (power laws -2/3,
        -8/3, -17/3 joined at 0.2 v/B and 0.3 v/D, normalized to the same
        variance), as ``--psd``.
    wind_angle_deg : float
        Wind direction from the baseline, degrees, -360 to 360 (0: along
        the baseline; the three-slope model accepts only 0 and 180), as
        ``--wind-angle-deg``.

    Returns
    -------
    dict
        ``detector``, ``bins``, ``reference``, ``baseline_m``, ``r0_m``,
        ``r0_over_v_s``, ``tau0_s``, ``piston_rms_um``, …, and ``results``: per
        frequency the bias and scatter of V1 and V2 with standard errors.
    """
    values = dict(locals())
    if fringe_hz is None:
        freqs = []
    elif isinstance(fringe_hz, (int, float, _np.integer, _np.floating)) and not isinstance(fringe_hz, bool):
        freqs = [_to_float("fringe_hz", fringe_hz)]
    else:
        freqs = [_to_float("fringe_hz", f) for f in fringe_hz]
    threads = _uint("threads", threads)
    if client is not None and threads == 0:
        threads = 1
    args = (
        _physical(values, exclude=("fringe_hz",)),
        freqs,
        _word("bins", bins),
        _uint("scans", scans),
        _uint("seed", seed),
        _v2ref.check_threads(threads),
        _word("psd", psd),
        _float("wind_angle_deg", wind_angle_deg),
    )
    if client is None and checkpoint is None:
        return _v2ref.piston(*args)
    from . import dask as _dask

    return _dask._run_units("piston", args, client, checkpoint, 1)[0]


#: The keyword arguments of :func:`plan` named as physical inputs that are
#: its grid instead.
_PLAN_GRID = ("fringe_hz", "stroke_um")


#: The keyword arguments given to the running :func:`plan`: its
#: ``instrument`` preset fills only the others, as the CLI's does the flags
#: not given (a keyword given at its default value included).
_GIVEN: "_contextvars.ContextVar[frozenset]" = _contextvars.ContextVar("v2ref_given", default=frozenset())


def _keywords_given(f):
    """``f`` recording in ``_GIVEN`` the keyword arguments it was given."""

    @_functools.wraps(f)
    def wrapper(*args, **kwargs):
        token = _GIVEN.set(frozenset(kwargs))
        try:
            return f(*args, **kwargs)
        finally:
            _GIVEN.reset(token)

    return wrapper


@_keywords_given
@_documented(exclude=_PLAN_GRID)
def plan(
    *,
    instrument: Optional[str] = None,
    target_sigma_v2: Optional[float] = None,
    time_budget_s: Optional[float] = None,
    photon_rate_per_s: Optional[float] = None,
    magnitude: Optional[float] = None,
    magnitude_band: Optional[str] = None,
    throughput: Optional[float] = None,
    samples_per_fringe: float = 4.0,
    dead_time_s: float = 0.0,
    frame_rate_hz: Optional[float] = None,
    fringe_hz: Optional[Sequence[float]] = None,
    stroke_um: Optional[Sequence[float]] = None,
    scans: int = 16000,
    seed: int = 1,
    threads: int = 0,
    diameter_err_mas: float = 0.0,
    oifits: Optional[_PathLike] = None,
    force: bool = False,
    target_name: Optional[str] = None,
    ra_deg: Optional[float] = None,
    dec_deg: Optional[float] = None,
    date: Optional[str] = None,
    site: Optional[str] = None,
    site_lon_deg: Optional[float] = None,
    site_lat_deg: Optional[float] = None,
    site_height_m: Optional[float] = None,
    bias: str = "counts",
    verify: bool = False,
    verify_observations: int = 256,
    client: Any = None,
    checkpoint: Optional[_PathLike] = None,
    # The physical keyword arguments (fields of the library's Physical).
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
    spectrum_csv: Optional[_PathLike] = None,
    source: str = "ud",
    diameter_mas: float = 43.0,
    spatial_freq_cpas: Optional[float] = None,
    baseline_m: Optional[float] = None,
    dispersion_pp_rad: float = 0.0,
    integrating: bool = False,
    visibility: float = 1.0,
    read_noise: float = 0.0,
    photon_noise: bool = True,
    wind_mps: float = 10.0,
    seeing_arcsec: float = 1.0,
    seeing_wavelength_um: Optional[float] = None,
    aperture_m: float = 0.45,
    outer_scale_m: Optional[float] = None,
    sub_samples: int = 6,
    reference: str = "mean",
) -> Dict[str, Any]:
    """The estimator, fringe frequency, stroke and scans that reach a target σ(V²), as ``v2ref plan --json``.

    Parameters
    ----------
    instrument : str, optional
        A preset's name (as ``v2ref plan --instrument``; ``v2ref plan
        --instrument list`` lists them, docs/instruments.md cites their
        values): its band, aperture, baseline, read noise, dead time, frame
        rate and throughput fill every keyword not given here (one given,
        even at its default value, is kept).
    target_sigma_v2 : float, optional
        σ of the averaged V² to reach (default 1e-3 when no time budget).
    time_budget_s : float, optional
        Instead, the time to spend, s: the σ reached is reported.
    photon_rate_per_s : float, optional
        Continuum photons per second at the detector in the band (default
        1e6; not with ``magnitude``).
    magnitude, magnitude_band, throughput : optional
        Instead of ``photon_rate_per_s`` (as ``v2ref plan --magnitude``):
        the source's magnitude (-10 to 30) in ``magnitude_band`` ("J", "H",
        "Ks", "V", "R", "I"), collected by two apertures of ``aperture_m``
        times ``throughput`` (0 < T <= 1); see :func:`photon_rate`. All
        three together.
    samples_per_fringe : float
        Samples per fringe at λ0 (δx = λ0 / this).
    dead_time_s : float
        Dead time between scans, s (the plan assumes none unless given).
    frame_rate_hz : float, optional
        The detector's maximum sample rate, Hz (as ``--frame-rate-hz``): the
        grid's fringe frequencies stop at ``frame_rate_hz /
        samples_per_fringe`` (the default grid runs up to it), and a
        recommendation there is the detector's edge (``at_detector_edge``).
    fringe_hz, stroke_um : sequence of float, optional
        The grid: fringe frequencies (Hz; default 20 from 20 to 2000, log)
        and strokes (µm; default 16, 32, 64, 128).
    scans : int
        Scans of each piston Monte Carlo (32 and more; cut into up to 16
        independent piston sequences, whose spread gives the errors).
    seed, threads : int
        Seed of the piston Monte Carlo; worker threads (0: all cores; the
        answer does not depend on it).
    diameter_err_mas : float
        1σ uncertainty of the uniform disk's diameter, mas (>= 0): its
        effect on V² is reported beside the corrections.
    oifits : path, optional
        Also write the predicted observation at the recommended setting as
        OIFITS v2 (as ``v2ref plan --oifits``): V², its predicted σ, and the
        biases left to correct in header keywords. Refused unless it ends
        in ``.fits``, ``.oifits`` or ``.fit`` (each possibly ``.gz``); not
        written when no setting reaches the target (``recommended`` null).
    force : bool
        Replace an existing ``oifits`` file (as ``--force``); without it an
        existing file is refused before any computing.
    target_name, ra_deg, dec_deg, date, site, site_lon_deg, site_lat_deg, site_height_m : optional
        Where and when the ``oifits`` file says the observation is made,
        as :func:`v2ref.oifits.write_oifits` takes them (refused without
        ``oifits``).
    bias : {"counts", "model"}
        Where the user's pipeline takes the photon-noise bias's counts from
        (as ``v2ref plan --bias``): each scan's own counts (unbiased for
        both estimators under piston) or the source model's piston-free
        counts (off by the piston's shift of the fringe: predicted and
        added to the bias). The predicted mean and the noise follow it.
    verify : bool
        Also simulate the recommended observation, n consecutive scans
        through one atmosphere with photon and detector noise, estimated
        with ``bias`` (as ``v2ref plan --verify``): ``verification`` holds
        the σ(V²) and mean achieved with intervals beside the promise.
    verify_observations : int
        Observations simulated by ``verify``: 32 to 1e6.
    client : dask.distributed.Client, optional
        Runs ``verify``'s simulated observations on this Dask cluster, a
        task per batch of piston sequences (the grid is planned here, in
        seconds); the answer is the one process's, bit for bit
        (``docs/dask.md``). Nothing to run there without ``verify``.
    checkpoint : path-like, optional
        A folder keeping each finished batch of ``verify``'s simulation, as
        :func:`simulate`'s; a rerun computes only the batches it lacks.
    {physical}

    Returns
    -------
    dict
        ``inputs``, ``points`` (every estimator × fringe frequency × stroke
        with each term: bandwidth and scan biases, noise and piston σ per
        scan, piston bias, scans, time; the fastest of each estimator with
        ``observation``, the error of their consecutive scans' mean),
        ``best_v1``, ``best_v2``, ``recommended``, and ``verification``
        with ``verify``.
    """
    arguments = _plan_arguments(dict(locals()))
    if instrument is not None:
        arguments["instrument"] = (_word("instrument", instrument), sorted(_GIVEN.get()))
    if verify and (client is not None or checkpoint is not None):
        from . import dask as _dask

        arguments["verify_units"] = _dask._plan_verify_units(arguments, client, checkpoint)
    return _v2ref.plan(**arguments)


def _plan_arguments(values: Mapping[str, Any]) -> Dict[str, Any]:
    """:func:`plan`'s keywords (all of them, defaults included) checked and
    converted into the extension's arguments; :func:`plan_targets` shares them."""
    from .oifits import _observing

    observing = _observing(values)
    oifits = values["oifits"]
    out = None if oifits is None else _os.fspath(oifits)
    if out is not None and not isinstance(out, str):
        raise TypeError(f"oifits: {oifits!r} is not a path")
    opt = lambda name, v: None if v is None else _float(name, v)
    if not isinstance(values["verify"], bool):
        raise TypeError(f"verify: {values['verify']!r} is not a bool")
    observations = _uint("verify_observations", values["verify_observations"])
    rate = values["photon_rate_per_s"]
    return dict(
        physical=_physical(values, exclude=_PLAN_GRID),
        samples_per_fringe=_float("samples_per_fringe", values["samples_per_fringe"]),
        photon_rate_per_s=_float("photon_rate_per_s", 1e6 if rate is None else rate),
        dead_time_s=_float("dead_time_s", values["dead_time_s"]),
        fringe_hz=[_to_float("fringe_hz", f) for f in (values["fringe_hz"] or [])],
        stroke_um=[_to_float("stroke_um", s) for s in (values["stroke_um"] or [])],
        target_sigma_v2=opt("target_sigma_v2", values["target_sigma_v2"]),
        time_budget_s=opt("time_budget_s", values["time_budget_s"]),
        scans=_uint("scans", values["scans"]),
        seed=_uint("seed", values["seed"]),
        threads=_v2ref.check_threads(_uint("threads", values["threads"])),
        diameter_err_mas=_float("diameter_err_mas", values["diameter_err_mas"]),
        oifits=out,
        bias=_word("bias", values["bias"]),
        verify_observations=observations if values["verify"] else None,
        observing=observing,
        force=_flag("force", values["force"]),
        magnitude=_plan_magnitude(
            rate,
            values["magnitude"],
            values["magnitude_band"],
            values["throughput"],
            values["spectrum_csv"],
            values.get("instrument") is not None,
        ),
        frame_rate_hz=opt("frame_rate_hz", values["frame_rate_hz"]),
    )


#: Keywords of :func:`plan` that :func:`plan_targets` does not take: it
#: writes no OIFITS file, and a row's coordinates are its own columns.
_NOT_FOR_TARGETS = (
    "oifits", "force", "target_name", "ra_deg", "dec_deg", "date",
    "site", "site_lon_deg", "site_lat_deg", "site_height_m",
)


def plan_targets(targets: Any, **keywords: Any) -> List[Dict[str, Any]]:
    """Plans every target of a list with :func:`plan`'s keywords shared, as ``v2ref plan --targets``.

    Parameters
    ----------
    targets : path, astropy Table or list of dicts
        The targets, one per row, with the columns ``name`` (required),
        ``magnitude`` and ``band`` (together: J, H, Ks, V, R, I),
        ``diameter_mas`` (the uniform disk's, mas), ``ra_deg`` and
        ``dec_deg`` (echoed, not used by the plan). A missing column, a
        None or a masked cell takes the shared keyword. A path is read as
        the CSV file of ``v2ref plan --targets``.
    **keywords
        Any keyword of :func:`plan` but its files and observing details
        (``oifits``, ``force``, ``target_name``, ``ra_deg`` ... ``site_height_m``):
        shared by every row, a row's cell overriding it. ``throughput``
        (without a shared ``magnitude``) is the rows' magnitudes'.
    client : dask.distributed.Client, optional
        Plans each row as a task on this Dask cluster (``pip install
        v2ref[dask]``); the table is the one-process table, bit for bit
        (``docs/dask.md``). A path is read here, not on the workers.
    progress : bool or callable, optional
        ``True``: a line on stderr at most once a second, the targets done,
        the time elapsed and about how long is left (as the CLI's bar and
        ETA). A callable: called ``progress(done, total)`` in the calling
        thread after each target (in list order here, as they finish on a
        cluster). Either way the rows are planned one call at a time (a
        list given as a path read once, here), the same table bit for bit.
    checkpoint : str or os.PathLike, optional
        A folder where each row's table rows are kept as they are planned
        (one file a row, written whole or not at all); run again with the
        same list and keywords, only the rows missing there are planned,
        the same table bit for bit. Entries are read as
        ``docs/threat-model.md`` says: a link is never followed, an entry
        of another list, other keywords or another version is not read.

    Returns
    -------
    list of dict
        One per target, in order, with the columns of the CSV table
        (``TARGET``, ``RAEP0``, ``DECEP0`` as OI_TARGET names them,
        ``line``, ``status`` ("ok", "unreachable" or "error"), ``reason``,
        the recommendation and its promise). A row that cannot be read or
        planned is marked ``error`` with its reason, not raised; ``line`` is
        its line in the file, or for a Table or list its index + 2 (its line
        in the same rows written as CSV under a header). Each row's seed is
        keyed by its content and ``seed``, so that its plan does not depend
        on its place or the other rows; ``astropy.table.Table(result)``
        makes a table of it.
    """
    client = keywords.pop("client", None)
    report = _progress.reporter(keywords.pop("progress", None))
    checkpoint = keywords.pop("checkpoint", None)
    for k in _NOT_FOR_TARGETS:
        if k in keywords:
            raise TypeError(f"{k}: not a keyword of plan_targets (no OIFITS file is written; a row's coordinates are its ra_deg, dec_deg)")
    throughput = None
    if keywords.get("magnitude") is None and keywords.get("throughput") is not None:
        throughput = _float("throughput", keywords.pop("throughput"))
    try:
        bound = _inspect.signature(plan).bind(**keywords)
    except TypeError as e:
        raise TypeError(f"plan_targets: {e}") from None
    bound.apply_defaults()
    args = _plan_arguments(bound.arguments)
    for k in ("oifits", "observing", "force"):
        del args[k]
    if keywords.get("instrument") is not None:
        args["instrument"] = (_word("instrument", keywords["instrument"]), sorted(keywords))
    path, text = _target_list(targets)
    if client is None and report is None and checkpoint is None:
        return _v2ref.plan_targets(path, text, throughput, **args)
    from . import dask as _dask

    return _dask._plan_targets(path, text, throughput, args, client, report, checkpoint)


def _target_list(targets: Any) -> Tuple[Optional[str], Optional[str]]:
    """A target list as the extension takes it: a path, or CSV text."""
    if isinstance(targets, (str, _os.PathLike)):
        return _utf8_path("targets", targets), None
    if hasattr(targets, "colnames"):
        names = list(targets.colnames)
        rows = [{c: row[c] for c in names} for row in targets]
    elif isinstance(targets, _abc.Sequence) and all(isinstance(r, _abc.Mapping) for r in targets):
        rows = list(targets)
    else:
        raise TypeError(f"targets: {type(targets).__name__} is not a path, an astropy Table or a list of dicts")
    columns: list = []
    for row in rows:
        for k in row:
            if not isinstance(k, str):
                raise TypeError(f"targets: the column name {k!r} is not a str")
            if k not in columns:
                columns.append(k)
    lines = [",".join(_csv_cell("targets", c) for c in columns)]
    for i, row in enumerate(rows):
        lines.append(",".join(_csv_cell(f"targets[{i}][{c!r}]", row.get(c)) for c in columns))
    return None, "\n".join(lines) + "\n"


def _csv_cell(name: str, v: Any) -> str:
    """One value as a CSV cell: None or masked empty, a float in full."""
    if v is None or _np.ma.is_masked(v):
        return ""
    if isinstance(v, _np.generic):
        v = v.item()
    text = repr(v) if isinstance(v, float) else str(v)
    if "\n" in text or "\r" in text:
        raise ValueError(f"{name}: {text!r} holds a line break")
    if any(c in text for c in ',"') or text != text.strip():
        text = '"' + text.replace('"', '""') + '"'
    return text


def _plan_magnitude(photon_rate_per_s, magnitude, magnitude_band, throughput, spectrum_csv, preset=False):
    """``plan``'s magnitude keywords as the extension takes them (None
    without ``magnitude``), refused half given or beside a photon rate."""
    given = {
        "magnitude": magnitude,
        "magnitude_band": magnitude_band,
        "throughput": throughput,
    }
    if magnitude is None:
        for name, v in given.items():
            if v is not None:
                raise ValueError(f"{name}: needs magnitude (with magnitude_band and throughput)")
        return None
    if photon_rate_per_s is not None:
        raise ValueError("photon_rate_per_s: give photon_rate_per_s or magnitude, not both")
    if spectrum_csv is not None:
        raise ValueError("magnitude: converted over the flat band (wavelength_um, bandwidth_nm), not with spectrum_csv")
    for name, v in given.items():
        if v is None and not (name == "throughput" and preset):
            raise ValueError(f"{name}: needed with magnitude (magnitude, magnitude_band and throughput together)")
    if not isinstance(magnitude_band, str):
        raise TypeError(f"magnitude_band: {magnitude_band!r} is not a str (J, H, Ks, V, R or I)")
    # Any case, as the CLI's --magnitude-band takes it (h, H; ks, Ks).
    bands = {b.lower(): b for b in ("J", "H", "Ks", "V", "R", "I")}
    band = bands.get(magnitude_band.strip().lower(), magnitude_band)
    # NaN: none given, the preset's (refused by the extension without one).
    rate_throughput = float("nan") if throughput is None else _float("throughput", throughput)
    return (_float("magnitude", magnitude), band, rate_throughput)


@_documented()
def photon_rate(
    magnitude: float,
    *,
    band: str,
    throughput: float,
    # The physical keyword arguments (fields of the library's Physical).
    aperture_m: float = 0.45,
    wavelength_um: float = 2.2,
    bandwidth_nm: float = 400.0,
) -> float:
    """Photons per second at the detector in the band from a magnitude, as ``v2ref plan --magnitude``.

    ``F_ν = F_ν0 10^(-m/2.5)`` with the zero points of Cohen, Wheaton &
    Megeath (2003, AJ 126, 1090, Table 2: 2MASS J 1594, H 1024, Ks 666.7 Jy)
    or Bessell, Castelli & Plez (1998, A&A 333, 231: Johnson–Cousins V
    3640, R 3080, I 2550 Jy), taken flat over [λ0 − Δλ/2, λ0 + Δλ/2]: ``F_ν ln(λmax/λmin)/h`` photons
    s⁻¹ m⁻², times the two apertures' area ``2 π D²/4`` and ``throughput``.
    Pass the result to :func:`plan` as ``photon_rate_per_s``.

    Parameters
    ----------
    magnitude : float
        The source's magnitude in ``band``, -10 to 30.
    band : {"J", "H", "Ks", "V", "R", "I"}
        The band of ``magnitude``: 2MASS J, H, Ks or Johnson–Cousins V, R, I
        (it must cover the observing band).
    throughput : float
        Fraction of the source's photons counted in the sampled
        interferogram (atmosphere, optics, combiner outputs sampled,
        detector QE), 0 < T <= 1.
    {physical}
    """
    return _v2ref.photon_rate(
        _float("magnitude", magnitude),
        band,
        _float("aperture_m", aperture_m),
        _float("throughput", throughput),
        _float("wavelength_um", wavelength_um),
        _float("bandwidth_nm", bandwidth_nm),
    )


def claims(*, quick: bool = False) -> list:
    """Every claim of the paper: printed value, computed value, status, as ``v2ref claims --json``.

    Parameters
    ----------
    quick : bool
        Smaller Monte Carlo runs (same code paths).

    Returns
    -------
    list of dict
        One entry per claim: ``id``, ``paper``, ``computed``, ``status``,
        ``note``, …
    """
    return _v2ref.claims(bool(quick))


# OIFITS (python/v2ref/oifits.py).
from .oifits import read_oifits, read_oifits_estimates, score_oifits, write_oifits, write_oifits_truth  # noqa: E402

__all__ += ["read_oifits", "read_oifits_estimates", "score_oifits", "write_oifits", "write_oifits_truth"]


# --------------------------------------------------------------------------
# The namespace: the API of ``__all__`` only.

del Any, Dict, Mapping, Optional, Sequence, Tuple, Union


def __dir__():
    """The public names: ``__all__``, the extension module and the dunders."""
    dunders = {n for n in globals() if n.startswith("__") and n.endswith("__")}
    return sorted(set(__all__) | {"_v2ref"} | dunders)
