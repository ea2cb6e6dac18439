"""Type stubs of the v2ref package (units in every parameter description).

Generated from the package's source by scripts/stub.py: do not edit.
"""

import os as _os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

_PathLike = Union[str, _os.PathLike[str]]

__version__: str
ESTIMATE_COLUMNS: Tuple[str, ...]

def estimate(interferograms: Any, *, sidecar: Union[Mapping[str, Any], _PathLike, None]=None, bins: str='positive', bias: str='model', calibrator: Any=None, continuum_subtracted: Optional[bool]=None, threads: int=0, wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, dx_um: float=0.5, integrating: bool=False, visibility: float=1.0, photons: float=10.0, read_noise: float=0.0, photon_noise: bool=True, fringe_hz: Optional[float]=None, wind_mps: float=10.0, seeing_arcsec: float=1.0, seeing_wavelength_um: Optional[float]=None, aperture_m: float=0.45, outer_scale_m: Optional[float]=None, sub_samples: int=6, reference: str='mean') -> Dict[str, _np.ndarray]:
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
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    dx_um : float, default 0.5
        Sample spacing δx, µm: > 0.
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).
    visibility : float, default 1.0
        Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point
        source (a source of known V: ``source`` point).
    photons : float, default 10.0
        Continuum n (c = n), photons per sample: > 0 to 1e12.
    read_noise : float, default 0.0
        Detector noise standard deviation σ_det, photons per sample: 0 to
        1e12.
    photon_noise : bool, default True
        Poisson photon noise (when off, detector noise only).
    fringe_hz : float, optional
        Fringe frequency f = v/λ0, Hz: 0.001 to 1e7. Adds the differential
        piston of §6 (consecutive scans through one piston sequence).
        Default: no piston.
    wind_mps : float, default 10.0
        Wind speed, m/s: 0.001 to 343. Frozen flow along the baseline.
    seeing_arcsec : float, default 1.0
        Seeing λ/r0, arcsec: 0 to 100. Quoted at ``seeing_wavelength_um``;
        0: no turbulence.
    seeing_wavelength_um : float, optional
        Wavelength at which ``seeing_arcsec`` is quoted, µm: 0.3 to 30. Site
        monitors quote 0.5. Converted to the observing wavelength by r0 ∝
        λ^(6/5). Default: the observing wavelength ``wavelength_um``.
    aperture_m : float, default 0.45
        Telescope aperture diameter, m: 0.001 to 1000.
    outer_scale_m : float, optional
        von Kármán outer scale, m: > 0. Default: infinite.
    sub_samples : int, default 6
        Sub-samples per sample of the integrating detector under piston: 1
        to 64.
    reference : str, default 'mean'
        Where the fringe packet sits in each scan: centre, mean or absolute.

    Returns
    -------
    dict of str to ndarray, shape (rows,) or (rows, C)
        ``v1_sq_raw``, ``v2_sq_raw`` (photons²), ``v1_sq_bias``,
        ``v2_sq_bias`` (photons²), ``v1_sq``, ``v2_sq`` (normalized,
        dimensionless): the columns of ``v2ref estimate``; (rows, C), one
        column per channel in increasing wavenumber, when the rows were
        given as (rows, C, N).
    """

def synthesize(*, rows: int=1000, seed: int=1, threads: int=0, reference_blocks: Optional[int]=None, keep_continuum: bool=False, layout: str='sequences', observations: int=1, dead_time_s: float=0.0, out: Optional[_PathLike]=None, force: bool=False, client: Any=None, checkpoint: Optional[_PathLike]=None, wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, stroke_um: Optional[float]=None, dx_um: float=0.5, samples: int=128, integrating: bool=False, visibility: float=1.0, photons: float=10.0, read_noise: float=0.0, photon_noise: bool=True, fringe_hz: Optional[float]=None, wind_mps: float=10.0, seeing_arcsec: float=1.0, seeing_wavelength_um: Optional[float]=None, aperture_m: float=0.45, outer_scale_m: Optional[float]=None, sub_samples: int=6, reference: str='mean') -> Tuple[_np.ndarray, Dict[str, Any]]:
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
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    stroke_um : float, optional
        OPD stroke Δx, µm: N = Δx/δx, rounded, from 2 to 2^24. Default:
        ``samples`` × ``dx_um``.
    dx_um : float, default 0.5
        Sample spacing δx, µm: > 0.
    samples : int, default 128
        Number of samples N: 2 to 2^24. Ignored when ``stroke_um`` is given.
        The finite scan costs about N² (N = 16384: about 10 s on two cores).
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).
    visibility : float, default 1.0
        Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point
        source (a source of known V: ``source`` point).
    photons : float, default 10.0
        Continuum n (c = n), photons per sample: > 0 to 1e12.
    read_noise : float, default 0.0
        Detector noise standard deviation σ_det, photons per sample: 0 to
        1e12.
    photon_noise : bool, default True
        Poisson photon noise (when off, detector noise only).
    fringe_hz : float, optional
        Fringe frequency f = v/λ0, Hz: 0.001 to 1e7. Adds the differential
        piston of §6 (consecutive scans through one piston sequence).
        Default: no piston.
    wind_mps : float, default 10.0
        Wind speed, m/s: 0.001 to 343. Frozen flow along the baseline.
    seeing_arcsec : float, default 1.0
        Seeing λ/r0, arcsec: 0 to 100. Quoted at ``seeing_wavelength_um``;
        0: no turbulence.
    seeing_wavelength_um : float, optional
        Wavelength at which ``seeing_arcsec`` is quoted, µm: 0.3 to 30. Site
        monitors quote 0.5. Converted to the observing wavelength by r0 ∝
        λ^(6/5). Default: the observing wavelength ``wavelength_um``.
    aperture_m : float, default 0.45
        Telescope aperture diameter, m: 0.001 to 1000.
    outer_scale_m : float, optional
        von Kármán outer scale, m: > 0. Default: infinite.
    sub_samples : int, default 6
        Sub-samples per sample of the integrating detector under piston: 1
        to 64.
    reference : str, default 'mean'
        Where the fringe packet sits in each scan: centre, mean or absolute.

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

def powered_set(name: str, *, client: Any=None, checkpoint: Optional[_PathLike]=None) -> Tuple[_np.ndarray, Dict[str, Any]]:
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

def score(estimates: Any, sidecar: Union[Mapping[str, Any], _PathLike], *, bins: str='positive', bias: str='model', alpha: float=0.001, columns: Optional[Sequence[str]]=None) -> Dict[str, Any]:
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

def simulate(*, trials: int=100000, seed: int=1, threads: int=0, bins: str='positive', bias: str='model', formula: str='exact', client: Any=None, checkpoint: Optional[_PathLike]=None, chunk_units: Optional[int]=None, wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, stroke_um: Optional[float]=None, dx_um: float=0.5, samples: int=128, integrating: bool=False, visibility: float=1.0, photons: float=10.0, read_noise: float=0.0, photon_noise: bool=True, fringe_hz: Optional[float]=None, wind_mps: float=10.0, seeing_arcsec: float=1.0, seeing_wavelength_um: Optional[float]=None, aperture_m: float=0.45, outer_scale_m: Optional[float]=None, sub_samples: int=6, reference: str='mean') -> Dict[str, Any]:
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
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    stroke_um : float, optional
        OPD stroke Δx, µm: N = Δx/δx, rounded, from 2 to 2^24. Default:
        ``samples`` × ``dx_um``.
    dx_um : float, default 0.5
        Sample spacing δx, µm: > 0.
    samples : int, default 128
        Number of samples N: 2 to 2^24. Ignored when ``stroke_um`` is given.
        The finite scan costs about N² (N = 16384: about 10 s on two cores).
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).
    visibility : float, default 1.0
        Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point
        source (a source of known V: ``source`` point).
    photons : float, default 10.0
        Continuum n (c = n), photons per sample: > 0 to 1e12.
    read_noise : float, default 0.0
        Detector noise standard deviation σ_det, photons per sample: 0 to
        1e12.
    photon_noise : bool, default True
        Poisson photon noise (when off, detector noise only).
    fringe_hz : float, optional
        Fringe frequency f = v/λ0, Hz: 0.001 to 1e7. Adds the differential
        piston of §6 (consecutive scans through one piston sequence).
        Default: no piston.
    wind_mps : float, default 10.0
        Wind speed, m/s: 0.001 to 343. Frozen flow along the baseline.
    seeing_arcsec : float, default 1.0
        Seeing λ/r0, arcsec: 0 to 100. Quoted at ``seeing_wavelength_um``;
        0: no turbulence.
    seeing_wavelength_um : float, optional
        Wavelength at which ``seeing_arcsec`` is quoted, µm: 0.3 to 30. Site
        monitors quote 0.5. Converted to the observing wavelength by r0 ∝
        λ^(6/5). Default: the observing wavelength ``wavelength_um``.
    aperture_m : float, default 0.45
        Telescope aperture diameter, m: 0.001 to 1000.
    outer_scale_m : float, optional
        von Kármán outer scale, m: > 0. Default: infinite.
    sub_samples : int, default 6
        Sub-samples per sample of the integrating detector under piston: 1
        to 64.
    reference : str, default 'mean'
        Where the fringe packet sits in each scan: centre, mean or absolute.

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

def bias(*, finite_scan: bool=False, bins: str='positive', wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, stroke_um: Optional[float]=None, dx_um: float=0.5, samples: int=128, integrating: bool=False) -> Dict[str, Any]:
    """Noise-free wide-band V1 and V2 for one configuration, as ``v2ref bias --json``.

    Parameters
    ----------
    finite_scan : bool
        Also compute the finite-scan estimators from a sampled interferogram
        (implied by ``stroke_um``).
    bins : {"positive", "band", "all"}
        Fourier bins of the finite-scan estimators.
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    stroke_um : float, optional
        OPD stroke Δx, µm: N = Δx/δx, rounded, from 2 to 2^24. Default:
        ``samples`` × ``dx_um``.
    dx_um : float, default 0.5
        Sample spacing δx, µm: > 0.
    samples : int, default 128
        Number of samples N: 2 to 2^24. Ignored when ``stroke_um`` is given.
        The finite scan costs about N² (N = 16384: about 10 s on two cores).
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).

    Returns
    -------
    dict
        ``v_mono``, ``v1``, ``v2``, ``v1_sq``, ``v2_sq``,
        ``spatial_freq_cpas``, ``sigma_eff_per_um`` (µm⁻¹), ``baseline_m``
        and, with a finite scan, ``finite_scan``; with spectral channels,
        ``channels``: per channel its wavelength range, photon share and
        biases (bandwidth, dispersion, finite scan, integrating detector).
    """

def snr(*, bins: str='positive', formula: str='exact', wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, stroke_um: Optional[float]=None, dx_um: float=0.5, samples: int=128, integrating: bool=False, visibility: float=1.0, photons: float=10.0, read_noise: float=0.0, photon_noise: bool=True) -> Dict[str, Any]:
    """Closed-form expectations, variances and SNRs of V1² and V2², as ``v2ref snr --json``.

    Parameters
    ----------
    bins : {"positive", "band", "all"}
        Window of the exact window statistics (``window_exact``).
    formula : {"exact", "published"}
        Formula: exact, or as printed in the paper's Appendix.
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    stroke_um : float, optional
        OPD stroke Δx, µm: N = Δx/δx, rounded, from 2 to 2^24. Default:
        ``samples`` × ``dx_um``.
    dx_um : float, default 0.5
        Sample spacing δx, µm: > 0.
    samples : int, default 128
        Number of samples N: 2 to 2^24. Ignored when ``stroke_um`` is given.
        The finite scan costs about N² (N = 16384: about 10 s on two cores).
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).
    visibility : float, default 1.0
        Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point
        source (a source of known V: ``source`` point).
    photons : float, default 10.0
        Continuum n (c = n), photons per sample: > 0 to 1e12.
    read_noise : float, default 0.0
        Detector noise standard deviation σ_det, photons per sample: 0 to
        1e12.
    photon_noise : bool, default True
        Poisson photon noise (when off, detector noise only).

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

def piston(*, fringe_hz: Union[float, Sequence[float], None]=None, scans: int=1000, seed: int=1, threads: int=0, bins: str='positive', client: Any=None, checkpoint: Optional[_PathLike]=None, wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, stroke_um: Optional[float]=None, dx_um: float=0.5, samples: int=128, integrating: bool=False, wind_mps: float=10.0, seeing_arcsec: float=1.0, seeing_wavelength_um: Optional[float]=None, aperture_m: float=0.45, outer_scale_m: Optional[float]=None, sub_samples: int=6, reference: str='mean', psd: str='two-aperture', wind_angle_deg: float=0.0) -> Dict[str, Any]:
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
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    stroke_um : float, optional
        OPD stroke Δx, µm: N = Δx/δx, rounded, from 2 to 2^24. Default:
        ``samples`` × ``dx_um``.
    dx_um : float, default 0.5
        Sample spacing δx, µm: > 0.
    samples : int, default 128
        Number of samples N: 2 to 2^24. Ignored when ``stroke_um`` is given.
        The finite scan costs about N² (N = 16384: about 10 s on two cores).
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).
    wind_mps : float, default 10.0
        Wind speed, m/s: 0.001 to 343. Frozen flow along the baseline.
    seeing_arcsec : float, default 1.0
        Seeing λ/r0, arcsec: 0 to 100. Quoted at ``seeing_wavelength_um``;
        0: no turbulence.
    seeing_wavelength_um : float, optional
        Wavelength at which ``seeing_arcsec`` is quoted, µm: 0.3 to 30. Site
        monitors quote 0.5. Converted to the observing wavelength by r0 ∝
        λ^(6/5). Default: the observing wavelength ``wavelength_um``.
    aperture_m : float, default 0.45
        Telescope aperture diameter, m: 0.001 to 1000.
    outer_scale_m : float, optional
        von Kármán outer scale, m: > 0. Default: infinite.
    sub_samples : int, default 6
        Sub-samples per sample of the integrating detector under piston: 1
        to 64.
    reference : str, default 'mean'
        Where the fringe packet sits in each scan: centre, mean or absolute.
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

def plan(*, instrument: Optional[str]=None, target_sigma_v2: Optional[float]=None, time_budget_s: Optional[float]=None, photon_rate_per_s: Optional[float]=None, magnitude: Optional[float]=None, magnitude_band: Optional[str]=None, throughput: Optional[float]=None, samples_per_fringe: float=4.0, dead_time_s: float=0.0, frame_rate_hz: Optional[float]=None, fringe_hz: Union[float, Sequence[float], None]=None, stroke_um: Union[float, Sequence[float], None]=None, scans: int=16000, seed: int=1, threads: int=0, diameter_err_mas: float=0.0, oifits: Optional[_PathLike]=None, force: bool=False, target_name: Optional[str]=None, ra_deg: Optional[float]=None, dec_deg: Optional[float]=None, date: Optional[str]=None, site: Optional[str]=None, site_lon_deg: Optional[float]=None, site_lat_deg: Optional[float]=None, site_height_m: Optional[float]=None, bias: str='counts', verify: bool=False, verify_observations: int=256, client: Any=None, checkpoint: Optional[_PathLike]=None, wavelength_um: float=2.2, bandwidth_nm: float=400.0, spectrum_csv: Optional[_PathLike]=None, channels: Optional[int]=None, resolution: Optional[float]=None, channels_csv: Optional[_PathLike]=None, source: str='ud', diameter_mas: float=43.0, spatial_freq_cpas: Optional[float]=None, baseline_m: Optional[float]=None, dispersion_pp_rad: float=0.0, integrating: bool=False, visibility: float=1.0, read_noise: float=0.0, photon_noise: bool=True, wind_mps: float=10.0, seeing_arcsec: float=1.0, seeing_wavelength_um: Optional[float]=None, aperture_m: float=0.45, outer_scale_m: Optional[float]=None, sub_samples: int=6, reference: str='mean') -> Dict[str, Any]:
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
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    spectrum_csv : path, optional
        A tabulated S(σ)F(σ) instead of the flat band: a CSV file of at most
        100000 rows, 16 MiB. Header `wavelength_um,weight` or
        `wavenumber_per_um,weight`, the weight per unit wavenumber
        (`weight_per_wavenumber` says so explicitly; `weight_per_um` is per
        unit wavelength and is converted by λ²); a leading byte-order mark
        is fine. Default: the flat band of ``wavelength_um`` and
        ``bandwidth_nm``.
    channels : int, optional
        Spectral channels C of equal width in wavenumber over the band: 1 to
        4096. bias, snr and simulate answer per channel (docs/conventions.md
        §16); one of ``channels``, ``resolution`` or ``channels_csv``. 1:
        the wide band's numbers. Default: the wide band, no channels.
    resolution : float, optional
        Channels of spectral resolution R = λ/Δλ across the band: > 0 (at
        most 4096 channels over the band). Geometric edges, the whole number
        of channels nearest R; each channel must hold a DFT bin of the scan.
        Default: the wide band, no channels.
    channels_csv : path, optional
        Channels' edges and responses from a table: a CSV file of at most
        4096 rows, 1 MiB. Header
        `wavelength_lo_um,wavelength_hi_um,response` or
        `wavenumber_lo_per_um,wavenumber_hi_per_um,response`, one row per
        channel by increasing axis value, the channels inside the band,
        neither overlapping nor out of order. Default: the wide band, no
        channels.
    source : str, default 'ud'
        Source model: point or ud. ud: a uniform disk of diameter
        ``diameter_mas``; point: unresolved (V = 1).
    diameter_mas : float, default 43.0
        Uniform-disk diameter θ, mas: > 0 to 3.6e6.
    spatial_freq_cpas : float, optional
        Spatial frequency S = B σ_eff, cycles/arcsec: 0 to 1e13 (and B =
        S/σ_eff at most 1e9 m). Default: 40, the paper's 18 m baseline in K
        (or from ``baseline_m``).
    baseline_m : float, optional
        Projected baseline B, m: 0 to 1e9. Instead of ``spatial_freq_cpas``.
        Default: from ``spatial_freq_cpas``.
    dispersion_pp_rad : float, default 0.0
        Quadratic dispersion phase, peak-to-peak over the band, rad: -1e4 to
        1e4.
    integrating : bool, default False
        Integrating detector (each sample averages the fringe over δx).
    visibility : float, default 1.0
        Visibility V scaling the fringe: 0 to 1. m_0 = n V for a point
        source (a source of known V: ``source`` point).
    read_noise : float, default 0.0
        Detector noise standard deviation σ_det, photons per sample: 0 to
        1e12.
    photon_noise : bool, default True
        Poisson photon noise (when off, detector noise only).
    wind_mps : float, default 10.0
        Wind speed, m/s: 0.001 to 343. Frozen flow along the baseline.
    seeing_arcsec : float, default 1.0
        Seeing λ/r0, arcsec: 0 to 100. Quoted at ``seeing_wavelength_um``;
        0: no turbulence.
    seeing_wavelength_um : float, optional
        Wavelength at which ``seeing_arcsec`` is quoted, µm: 0.3 to 30. Site
        monitors quote 0.5. Converted to the observing wavelength by r0 ∝
        λ^(6/5). Default: the observing wavelength ``wavelength_um``.
    aperture_m : float, default 0.45
        Telescope aperture diameter, m: 0.001 to 1000.
    outer_scale_m : float, optional
        von Kármán outer scale, m: > 0. Default: infinite.
    sub_samples : int, default 6
        Sub-samples per sample of the integrating detector under piston: 1
        to 64.
    reference : str, default 'mean'
        Where the fringe packet sits in each scan: centre, mean or absolute.

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

def photon_rate(magnitude: float, *, band: str, throughput: float, aperture_m: float=0.45, wavelength_um: float=2.2, bandwidth_nm: float=400.0) -> float:
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
    aperture_m : float, default 0.45
        Telescope aperture diameter, m: 0.001 to 1000.
    wavelength_um : float, default 2.2
        Centre wavelength λ0, µm: 0.001 to 100000. With ``spectrum_csv`` it
        still sets λ0 of the fringe frequency f = v/λ0, of the samples per
        fringe and of the seeing: give the spectrum's centre.
    bandwidth_nm : float, default 400.0
        Full bandwidth Δλ, nm: 1e-12 λ0 to under 2 λ0. The band [λ0 − Δλ/2,
        λ0 + Δλ/2], flat per unit wavenumber σ = 1/λ (not per unit
        wavelength: W(σ) is constant between 1/(λ0 + Δλ/2) and 1/(λ0 −
        Δλ/2)).
    """

def claims(*, quick: bool=False) -> list:
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

def read_oifits(path: Any, *, insname: Optional[str]=None, target: Optional[str]=None, accept_checksum_mismatch: bool=False) -> List[Dict[str, Any]]:
    """The ``OI_VIS2`` tables of an OIFITS file (v1 or v2), in file order.

    ``insname`` keeps the tables of that INSNAME, ``target`` (a TARGET name
    or a TARGET_ID) the rows of that target, as ``score`` chooses them
    (leading and trailing blanks of a name are not significant; a table with
    no row of the target is left out); None keeps all. Each table is a dict:
    ``insname``, ``estimator`` (``"v1_sq"``, ``"v2_sq"`` from v2ref's
    ``V2R_EST`` keyword, else None), ``revn``, ``hdu``, ``eff_wave_m`` and
    ``eff_band_m`` (metres, one per channel, from the ``OI_WAVELENGTH`` of
    its INSNAME), per row ``target_id``, ``mjd`` (days), ``ucoord_m`` and
    ``vcoord_m`` (metres; NaN where the table has no such column), and
    ``vis2data``, ``vis2err``, ``flag`` of shape (rows, channels). A
    malformed file raises ValueError; so does one whose CHECKSUM or DATASUM
    no longer match its bytes, unless ``accept_checksum_mismatch``. What
    was accepted but should be known (an HDU without checksums in a signed
    file, a v2ref file whose HDUs were added or removed) is a UserWarning.
    ``.fits.gz`` is read as well.
    """

def write_oifits(path: Any, *, sidecar: Any, v1_sq: Any=None, v2_sq: Any=None, bins: str='positive', bias: str='model', target_name: Optional[str]=None, ra_deg: Optional[float]=None, dec_deg: Optional[float]=None, date: Optional[str]=None, site: Optional[str]=None, site_lon_deg: Optional[float]=None, site_lat_deg: Optional[float]=None, site_height_m: Optional[float]=None, force: bool=False) -> None:
    """Writes per-row estimates of a synth set as OIFITS v2 (``.fits``).

    One ``OI_VIS2`` table per array given (INSNAME ``V2REF_V1SQ``,
    ``V2REF_V2SQ``), one row per interferogram; ``VIS2ERR`` is the
    closed-form standard deviation of the estimator at the set's
    conditions. The configuration (band, baseline) comes from ``sidecar``
    (a dict from ``synthesize()`` or a path). Written atomically; an
    existing file is replaced only with ``force=True`` (as ``--force``),
    never a link, a folder or a special file.

    Where and when the file says the observation was made (each left out
    keeps the default): ``target_name`` (TARGET, 1 to 16 printable ASCII
    characters; ``V2REF_MODEL``), ``ra_deg`` and ``dec_deg`` together (the
    target's J2000 position, degrees: 0 to 360 and -90 to 90; 0, 0),
    ``date`` (DATE-OBS, UTC, when the first row starts: ``YYYY-MM-DD`` or
    ``YYYY-MM-DDThh:mm:ss[.s]`` from 1858-11-17; ``2000-01-01``), ``site``
    (``"iota"``, ``"vlti"``, ``"chara"``, or the name of the site that
    ``site_lon_deg``, ``site_lat_deg`` (degrees, WGS84) and ``site_height_m``
    (m above the ellipsoid, -500 to 6000) place; ``"iota"``). A bad value
    raises ValueError naming the keyword, as the CLI's flags do.
    """

def write_oifits_truth(path: Any, *, sidecar: Any, target_name: Optional[str]=None, ra_deg: Optional[float]=None, dec_deg: Optional[float]=None, date: Optional[str]=None, site: Optional[str]=None, site_lon_deg: Optional[float]=None, site_lat_deg: Optional[float]=None, site_height_m: Optional[float]=None, force: bool=False) -> None:
    """Writes a synth set's truth (the expected V1², V2² of every row,
    window positive, convention model) as OIFITS v2; an existing file is
    replaced only with ``force=True``.
    Where and when the file says the observation was made (each left out
    keeps the default): ``target_name`` (TARGET, 1 to 16 printable ASCII
    characters; ``V2REF_MODEL``), ``ra_deg`` and ``dec_deg`` together (the
    target's J2000 position, degrees: 0 to 360 and -90 to 90; 0, 0),
    ``date`` (DATE-OBS, UTC, when the first row starts: ``YYYY-MM-DD`` or
    ``YYYY-MM-DDThh:mm:ss[.s]`` from 1858-11-17; ``2000-01-01``), ``site``
    (``"iota"``, ``"vlti"``, ``"chara"``, or the name of the site that
    ``site_lon_deg``, ``site_lat_deg`` (degrees, WGS84) and ``site_height_m``
    (m above the ellipsoid, -500 to 6000) place; ``"iota"``). A bad value
    raises ValueError naming the keyword, as the CLI's flags do.
    """

def score_oifits(path: Any, *, sidecar: Any, bins: str='positive', bias: str='model', alpha: float=0.001, insname: Optional[str]=None, estimator: Optional[str]=None, target: Optional[str]=None, accept_checksum_mismatch: bool=False) -> Dict[str, Any]:
    """Scores an OIFITS file of per-row estimates, as ``v2ref score
    --estimates FILE.fits --json``: FLAGged rows left out and counted
    (``flagged``); when fewer than half the set's rows are left, no score
    but ``verdict`` "too few rows" and ``pass`` False. ``insname``,
    ``estimator``, ``target`` choose tables and rows as the CLI's flags do;
    ``accept_checksum_mismatch`` reads a file whose CHECKSUM or DATASUM no
    longer match (refused otherwise).
    """

def read_oifits_estimates(path: Any, *, sidecar: Any, insname: Optional[str]=None, estimator: Optional[str]=None, target: Optional[str]=None, bins: str='positive', bias: str='model', accept_checksum_mismatch: bool=False) -> Dict[str, Any]:
    """A pipeline's estimates from OIFITS, matched to a set's rows in order,
    as ``v2ref score`` reads them.

    Returns ``v1_sq`` and ``v2_sq`` (arrays of the unflagged rows, or None),
    ``rows`` (in the file) and ``flagged`` (left out). ``insname`` chooses
    the tables when there are several; ``estimator`` (``"v1_sq"`` or
    ``"v2_sq"``) says what tables without v2ref's keyword hold; ``target``
    (a TARGET name or TARGET_ID) chooses the rows when they are of several
    targets. A table whose ``V2R_BINS`` or ``V2R_BIAS`` differs from
    ``bins`` or ``bias`` is refused; so is a file whose checksums no
    longer match, unless ``accept_checksum_mismatch``.
    """
