"""OIFITS (v2 written, v1 and v2 read) from Python, with the Rust library's
own reader and writer (both safe Rust): NumPy arrays
in and out. The files are those of ``v2ref estimate --out FILE.fits``,
``v2ref synth --oifits`` and ``v2ref score --estimates FILE.fits``.
"""

import os as _os
import warnings as _warnings
from typing import Any, Dict, List, Optional

import numpy as _np

from . import _v2ref
from ._arguments import _float, _sidecar_arg, _utf8_path


def _path(name: str, value: Any) -> str:
    if isinstance(value, (str, bytes, _os.PathLike)):
        return _utf8_path(name, value)
    raise TypeError(f"{name}: {type(value).__name__} is not a path")


def _column(name: str, x: Any, rows: Optional[int] = None) -> Optional[_np.ndarray]:
    if x is None:
        return None
    try:
        a = _np.ascontiguousarray(x, dtype=_np.float64)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{name}: not an array of numbers ({e})") from None
    if a.ndim != 1:
        raise ValueError(f"{name}: {a.ndim}-D array; one value per row (1-D) is needed")
    return a


#: The keywords that say where and when an OIFITS file's observation was
#: made, as ``--target-name`` ... ``--site-height-m`` of the CLI.
OBSERVING_KEYWORDS = (
    "target_name",
    "ra_deg",
    "dec_deg",
    "date",
    "site",
    "site_lon_deg",
    "site_lat_deg",
    "site_height_m",
)
_OBSERVING_TEXT = ("target_name", "date", "site")


def _observing(values: Dict[str, Any]) -> Optional[tuple]:
    """The observing keywords of ``values`` (types checked) as the Rust
    functions take them; None when none is given (every default)."""
    out = []
    for name in OBSERVING_KEYWORDS:
        v = values.get(name)
        if v is None:
            out.append(None)
        elif name in _OBSERVING_TEXT:
            if not isinstance(v, str):
                raise TypeError(f"{name}: {v!r} is not a string")
            out.append(v)
        else:
            out.append(_float(name, v))
    return None if all(v is None for v in out) else tuple(out)


_OBSERVING_DOC = """
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


def _notes(path: str, answer: Dict[str, Any]) -> Dict[str, Any]:
    """``answer`` without its ``notes``, each issued as a UserWarning: what
    the reader accepted that a caller should know (HDUs without checksums in
    a signed file, a v2ref file edited after it was written)."""
    for note in answer.pop("notes", ()):
        _warnings.warn(f"{path}: {note}", UserWarning, stacklevel=3)
    return answer


def read_oifits(
    path: Any,
    *,
    insname: Optional[str] = None,
    target: Optional[str] = None,
    accept_checksum_mismatch: bool = False,
) -> List[Dict[str, Any]]:
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
    name = _path("path", path)
    _optional_str("insname", insname)
    _optional_str("target", target)
    answer = _v2ref.read_oifits(name, insname, target, _flag("accept_checksum_mismatch", accept_checksum_mismatch))
    return _notes(name, answer)["tables"]


def write_oifits(
    path: Any,
    *,
    sidecar: Any,
    v1_sq: Any = None,
    v2_sq: Any = None,
    bins: str = "positive",
    bias: str = "model",
    target_name: Optional[str] = None,
    ra_deg: Optional[float] = None,
    dec_deg: Optional[float] = None,
    date: Optional[str] = None,
    site: Optional[str] = None,
    site_lon_deg: Optional[float] = None,
    site_lat_deg: Optional[float] = None,
    site_height_m: Optional[float] = None,
    force: bool = False,
) -> None:
    """Writes per-row estimates of a synth set as OIFITS v2 (``.fits``).

    One ``OI_VIS2`` table per array given (INSNAME ``V2REF_V1SQ``,
    ``V2REF_V2SQ``), one row per interferogram; ``VIS2ERR`` is the
    closed-form standard deviation of the estimator at the set's
    conditions. The configuration (band, baseline) comes from ``sidecar``
    (a dict from ``synthesize()`` or a path). Written atomically; an
    existing file is replaced only with ``force=True`` (as ``--force``),
    never a link, a folder or a special file.
    """
    observing = _observing(locals())
    text, name = _sidecar_arg(sidecar)
    a1 = _column("v1_sq", v1_sq)
    a2 = _column("v2_sq", v2_sq)
    if not isinstance(bins, str):
        raise TypeError(f"bins: {bins!r} is not a string")
    if not isinstance(bias, str):
        raise TypeError(f"bias: {bias!r} is not a string")
    _v2ref.write_oifits(_path("path", path), a1, a2, text, name, bins, bias, observing, _flag("force", force))


def write_oifits_truth(
    path: Any,
    *,
    sidecar: Any,
    target_name: Optional[str] = None,
    ra_deg: Optional[float] = None,
    dec_deg: Optional[float] = None,
    date: Optional[str] = None,
    site: Optional[str] = None,
    site_lon_deg: Optional[float] = None,
    site_lat_deg: Optional[float] = None,
    site_height_m: Optional[float] = None,
    force: bool = False,
) -> None:
    """Writes a synth set's truth (the expected V1², V2² of every row,
    window positive, convention model) as OIFITS v2; an existing file is
    replaced only with ``force=True``."""
    observing = _observing(locals())
    text, name = _sidecar_arg(sidecar)
    _v2ref.write_oifits_truth(_path("path", path), text, name, observing, _flag("force", force))


write_oifits.__doc__ = (write_oifits.__doc__ or "") + _OBSERVING_DOC
write_oifits_truth.__doc__ = (write_oifits_truth.__doc__ or "") + _OBSERVING_DOC


def _optional_str(name: str, value: Any) -> None:
    if value is not None and not isinstance(value, str):
        raise TypeError(f"{name}: {value!r} is not a string")


def _flag(name: str, value: Any) -> bool:
    if not isinstance(value, bool):
        raise TypeError(f"{name}: {value!r} is not True or False")
    return value


#: The extensions of an OIFITS path (any case; each possibly ``.gz``).
FITS_SUFFIXES = (".fits", ".oifits", ".fit", ".fits.gz", ".oifits.gz", ".fit.gz")


def is_fits_path(path: Any) -> bool:
    """True for a path (str, bytes, os.PathLike) ending in an OIFITS extension."""
    if not isinstance(path, (str, bytes, _os.PathLike)):
        return False
    return _os.fsdecode(path).lower().endswith(FITS_SUFFIXES)


def score_oifits(
    path: Any,
    *,
    sidecar: Any,
    bins: str = "positive",
    bias: str = "model",
    alpha: float = 1e-3,
    insname: Optional[str] = None,
    estimator: Optional[str] = None,
    target: Optional[str] = None,
    accept_checksum_mismatch: bool = False,
) -> Dict[str, Any]:
    """Scores an OIFITS file of per-row estimates, as ``v2ref score
    --estimates FILE.fits --json``: FLAGged rows left out and counted
    (``flagged``); when fewer than half the set's rows are left, no score
    but ``verdict`` "too few rows" and ``pass`` False. ``insname``,
    ``estimator``, ``target`` choose tables and rows as the CLI's flags do;
    ``accept_checksum_mismatch`` reads a file whose CHECKSUM or DATASUM no
    longer match (refused otherwise)."""
    text, name = _sidecar_arg(sidecar)
    for n, v in (("bins", bins), ("bias", bias), ("insname", insname), ("estimator", estimator), ("target", target)):
        _optional_str(n, v)
    file = _path("path", path)
    answer = _v2ref.score_oifits(
        file,
        text,
        name,
        bins,
        bias,
        _float("alpha", alpha),
        insname,
        estimator,
        target,
        _flag("accept_checksum_mismatch", accept_checksum_mismatch),
    )
    return _notes(file, answer)


def read_oifits_estimates(
    path: Any,
    *,
    sidecar: Any,
    insname: Optional[str] = None,
    estimator: Optional[str] = None,
    target: Optional[str] = None,
    bins: str = "positive",
    bias: str = "model",
    accept_checksum_mismatch: bool = False,
) -> Dict[str, Any]:
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
    text, name = _sidecar_arg(sidecar)
    for n, v in (("insname", insname), ("estimator", estimator), ("target", target), ("bins", bins), ("bias", bias)):
        _optional_str(n, v)
    file = _path("path", path)
    answer = _v2ref.read_oifits_estimates(
        file,
        text,
        name,
        insname,
        estimator,
        target,
        bins,
        bias,
        _flag("accept_checksum_mismatch", accept_checksum_mismatch),
    )
    return _notes(file, answer)
