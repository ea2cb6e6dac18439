"""The validation oracle: the reference estimates of a 2-D array of
interferograms (:func:`estimate`), test sets with their truth
(:func:`synthesize`, :func:`powered_set`), and a pipeline's estimates
scored against a set's truth (:func:`score`).
"""

import collections.abc as _abc
import json as _json
import os as _os
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _v2ref
from ._arguments import (
    _DEFAULTS,
    _PathLike,
    _documented,
    _flag,
    _float,
    _channel_rows,
    _matrix,
    _not_masked,
    _physical,
    _sidecar_arg,
    _uint,
    _vector,
    _word,
)

#: The columns of :func:`estimate`'s answer, in the order of ``v2ref estimate``.
ESTIMATE_COLUMNS = tuple(_v2ref.ESTIMATE_COLUMNS)


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
    channels: Optional[int] = None,
    resolution: Optional[float] = None,
    channels_csv: Optional[_PathLike] = None,
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
    interferograms : array_like, shape (rows, N) or (rows, C, N)
        One scan per row, columns in the order of the sidecar's
        ``sample_opd_um`` (column 0 at the white-light fringe); photons per
        sample. N is the array's width. A dispersed set (a sidecar with
        ``channels``, or the ``channels``, ``resolution`` or
        ``channels_csv`` keyword) takes its C channels of N samples as
        shape (rows, C, N), each channel estimated with its own model;
        another shape is a ValueError naming the shape needed. A
        C-contiguous float64 array is used without a copy; other real
        dtypes are converted.
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
    calibrator : array_like, shape (rows', N) or (rows', C, N), optional
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
    dict of str to ndarray, shape (rows,) or (rows, C)
        ``v1_sq_raw``, ``v2_sq_raw`` (photons²), ``v1_sq_bias``,
        ``v2_sq_bias`` (photons²), ``v1_sq``, ``v2_sq`` (normalized,
        dimensionless): the columns of ``v2ref estimate``; (rows, C), one
        column per channel in increasing wavenumber, when the rows were
        given as (rows, C, N).
    """
    values = dict(locals())
    data, channel_axis = _channel_rows("interferograms", interferograms)
    bins = _word("bins", bins)
    bias = _word("bias", bias)
    threads = _v2ref.check_threads(_uint("threads", threads))
    cal = None
    if calibrator is not None:
        cal, cal_axis = _channel_rows("calibrator", calibrator)
        if cal_axis != channel_axis:
            raise ValueError(
                f"calibrator: shape {_np.shape(calibrator)}; the interferograms have shape "
                f"{_np.shape(interferograms)}: the same channels of the same N are needed"
            )
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
        physical["samples"] = data.shape[1] // (channel_axis or 1)
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
        channel_axis,
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
    channels: Optional[int] = None,
    resolution: Optional[float] = None,
    channels_csv: Optional[_PathLike] = None,
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
    (ndarray of shape (rows, N) or (rows, C, N), dict)
        The interferograms (float64, photons per sample; with the
        ``channels``, ``resolution`` or ``channels_csv`` keyword and C > 1
        channels, shape (rows, C, N), channel after channel in increasing
        wavenumber, and the sidecar's ``channels`` lists each channel with
        its own truth; ``out`` writes the ``.npy`` of that shape) and the
        sidecar:
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


def _channel_estimate_columns(estimates: Any) -> Optional[Tuple[Optional[_np.ndarray], Optional[_np.ndarray]]]:
    """(v1_sq, v2_sq) of a dispersed set's estimates, each (rows, C) or
    None when absent; None when ``estimates`` is not a mapping of 2-D
    arrays (the wide-band estimates)."""
    if not isinstance(estimates, _abc.Mapping):
        return None
    if not any(_np.ndim(v) == 2 for v in estimates.values()):
        return None
    unknown = [k for k in estimates if k not in _ESTIMATE_KEYS]
    if unknown:
        raise ValueError(
            f"estimates: unknown key(s) {', '.join(map(repr, unknown))}; accepted keys: "
            f"{', '.join(_ESTIMATE_KEYS)} (v1_sq and v2_sq are scored; keys are case-sensitive)"
        )
    out = []
    for k in ("v1_sq", "v2_sq"):
        if k not in estimates:
            out.append(None)
            continue
        _not_masked(f"estimates[{k!r}]", estimates[k])
        a = _np.asarray(estimates[k])
        if a.ndim != 2 or not (_np.issubdtype(a.dtype, _np.floating) or _np.issubdtype(a.dtype, _np.integer)):
            raise ValueError(
                f"estimates[{k!r}]: array of shape {a.shape} and dtype {a.dtype}; a dispersed set's "
                "estimates are real arrays of shape (rows, C), one column per channel"
            )
        out.append(_np.ascontiguousarray(a, dtype=_np.float64))
    if out[0] is None and out[1] is None:
        raise ValueError(
            f"estimates: no column named v1_sq or v2_sq (found: {','.join(map(str, estimates))}); one of them is needed"
        )
    return out[0], out[1]


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
        :func:`estimate`; for a dispersed set arrays of shape (rows, C),
        one column per channel in increasing wavenumber, each channel
        scored against its own truth under one threshold), a structured array with those fields, or a 2-D
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
        minimum detectable biases, pass), ``pass``. For a dispersed set
        the library's ``ChannelScoreReport``: ``alpha``, ``tests`` (2 per
        estimator per channel), ``z_crit``, ``channels`` (per channel its
        ``estimators`` and ``pass``), ``pass``, with ``sidecar``,
        ``estimates``, ``bins``, ``bias``, ``rows``.
    """
    from .oifits import FITS_SUFFIXES, is_fits_path, score_oifits

    if is_fits_path(estimates) and columns is None:
        # An OIFITS path: read as `v2ref score --estimates FILE.fits`.
        return score_oifits(estimates, sidecar=sidecar, bins=bins, bias=bias, alpha=alpha)
    if isinstance(estimates, (str, bytes, _os.PathLike)):
        # Not an array of one value (a 0-D array of the path's text).
        raise TypeError(
            f"estimates: {_os.fsdecode(estimates)!r} is a path, and score reads only OIFITS files "
            f"({', '.join(FITS_SUFFIXES)}, without columns=); accepted: the estimates as an array "
            "or a mapping of v1_sq/v2_sq arrays (load a .npy or .csv with numpy first), or an OIFITS path"
        )
    text, name = _sidecar_arg(sidecar)
    _check_rows(estimates, text)
    alpha = _float("alpha", alpha)
    dispersed = _channel_estimate_columns(estimates)
    if dispersed is not None:
        # A dispersed set: each channel against its own truth, one
        # threshold for every test of every channel.
        return _v2ref.score_channels_answer(
            *dispersed, text, name, "<array>", _word("bins", bins), _word("bias", bias), alpha
        )
    v1, v2 = _estimate_columns(estimates, columns)
    return _v2ref.score(
        v1,
        v2,
        text,
        name,
        "<array>",
        _word("bins", bins),
        _word("bias", bias),
        alpha,
    )
