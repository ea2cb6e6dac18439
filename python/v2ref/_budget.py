"""The bias and noise budget of one configuration: the noise-free
wide-band biases (:func:`bias`), the closed-form variances and SNRs
(:func:`snr`), and the Monte Carlos of the normalized estimators
(:func:`simulate`) and of the differential piston (:func:`piston`).
"""

from typing import Any, Dict, Optional, Sequence, Union

from . import _v2ref
from ._arguments import _PathLike, _count, _documented, _flag, _float, _grid, _physical, _uint, _word


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
        Work units (8192 rows each) per task, 1 or more (default: about
        four tasks per worker thread, at least
        ``v2ref.dask.MIN_UNITS_PER_TASK``); checked, and used with
        ``client`` or ``checkpoint``.
    {physical}

    Returns
    -------
    dict
        ``mean_v1_sq``, ``var_v1_sq``, their standard errors and closed-form
        expectations (None with piston), the same for V2², ``trials``,
        ``seed``, ``piston``, ``piston_effect`` and every input. With
        spectral channels (``channels``, ``resolution`` or ``channels_csv``):
        ``channels`` (per channel its place, ``v1_sq`` and ``v2_sq``
        summaries), ``combined_v1_sq`` and ``combined_v2_sq`` (correlation
        matrix, the photon-weighted mean, its measured ``sigma`` and the
        ``independent_sigma`` of independent channels), as ``v2ref simulate
        --json``; ``client`` and ``checkpoint`` do not take channels yet.
    """
    values = dict(locals())
    threads = _uint("threads", threads)
    if chunk_units is not None:
        chunk_units = _count("chunk_units", chunk_units, 1)
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
        and, with a finite scan, ``finite_scan``; with spectral channels,
        ``channels``: per channel its wavelength range, photon share and
        biases (bandwidth, dispersion, finite scan, integrating detector).
    """
    values = dict(locals())
    return _v2ref.bias(_physical(values), _word("bins", bins), _flag("finite_scan", finite_scan))


@_documented()
def snr(
    *,
    bins: str = "positive",
    formula: str = "exact",
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
        the exact window statistics take); with spectral channels,
        ``channels`` (per channel the closed-form mean, sigma and SNR of V1²
        and V2²) and ``combined`` (their photon-weighted mean, sigma
        assuming independent channels).
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
        Fringe frequencies f = v/λ0, Hz (default: 300 and 1000): a number,
        or a list, tuple, range or 1-D array of numbers (an empty one: the
        default). A string is refused: the CLI's ``A:B:N`` is
        ``numpy.linspace(A, B, N)`` here, ``A:B:N:log``
        ``numpy.geomspace(A, B, N)``.
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
    freqs = _grid("fringe_hz", fringe_hz, "Hz")
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
