"""Observation planning: the estimator, fringe frequency, stroke and
scans that reach a target σ(V²) (:func:`plan`), for every target of a list
(:func:`plan_targets`), and a magnitude's photon rate
(:func:`photon_rate`).
"""

import collections.abc as _abc
import contextvars as _contextvars
import functools as _functools
import inspect as _inspect
import os as _os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _progress, _v2ref
from ._arguments import (
    _PathLike,
    _documented,
    _flag,
    _float,
    _grid,
    _physical,
    _uint,
    _utf8_path,
    _word,
)


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
    fringe_hz: Union[float, Sequence[float], None] = None,
    stroke_um: Union[float, Sequence[float], None] = None,
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
    channels: Optional[int] = None,
    resolution: Optional[float] = None,
    channels_csv: Optional[_PathLike] = None,
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
    fringe_hz, stroke_um : float or sequence of float, optional
        The grid: fringe frequencies (Hz; default 20 from 20 to 2000, log)
        and strokes (µm; default 16, 32, 64, 128); a number, or a list,
        tuple, range or 1-D array of numbers (an empty one: the default).
        A string is refused: the CLI's ``A:B:N`` is ``numpy.linspace(A, B,
        N)`` here, ``A:B:N:log`` ``numpy.geomspace(A, B, N)``.
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
    if client is not None or checkpoint is not None:
        from . import dask as _dask

        # Refused by name even when there is nothing to run on them.
        _dask._check_client(client)
        if checkpoint is not None:
            _dask._checked_path(checkpoint)
        if verify:
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
        fringe_hz=_grid("fringe_hz", values["fringe_hz"], "Hz"),
        stroke_um=_grid("stroke_um", values["stroke_um"], "µm"),
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
        (``docs/dask.md``). The list is read once, here; a task is sent
        its row, not the list. Anything without ``submit`` is refused
        (TypeError).
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
        the same table bit for bit. The folder is made if missing (its
        parent must exist). An entry is used only when it is this user's
        and its digest, key, row, line and name are this list's (an edited
        list or spectrum CSV, other keywords or another version are
        another key); a damaged one is refused naming it (ValueError),
        another user's is planned again with a warning
        (``docs/dask.md``).

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
        line = ",".join(_csv_cell(f"targets[{i}][{c!r}]", row.get(c)) for c in columns)
        # A row of empty cells stays a row (a blank line is skipped): its
        # first cell written as a quoted empty one.
        lines.append(line if line.strip() else '""' + line)
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
    # Quoted: a comma, a quote, blanks at an end, or a leading "#" (a line
    # starting with "#" is a comment of the list).
    if any(c in text for c in ',"') or text != text.strip() or text.startswith("#"):
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
    # Each number's type first: a string is refused as such, not as half given.
    for name in ("magnitude", "throughput"):
        if given[name] is not None:
            _float(name, given[name])
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
