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

# The functions live in modules by idea: the validation oracle (_oracle),
# one configuration's bias and noise budget (_budget), observation planning
# (_plan), OIFITS (oifits); the argument checks they share in _arguments.
from . import _v2ref
from ._budget import bias, piston, simulate, snr
from ._oracle import ESTIMATE_COLUMNS, estimate, powered_set, score, synthesize
from ._plan import photon_rate, plan, plan_targets
from .oifits import read_oifits, read_oifits_estimates, score_oifits, write_oifits, write_oifits_truth

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
    from ._arguments import _flag

    return _v2ref.claims(_flag("quick", quick))


# OIFITS (python/v2ref/oifits.py).
__all__ += ["read_oifits", "read_oifits_estimates", "score_oifits", "write_oifits", "write_oifits_truth"]

# A function defined in a private module is the API's v2ref.NAME: help()
# names this module, and pickle refers to it here, not by a private path.
for _name in __all__:
    if getattr(globals()[_name], "__module__", "").startswith(__name__ + "._"):
        globals()[_name].__module__ = __name__
del _name


# --------------------------------------------------------------------------
# The namespace: the API of ``__all__`` only.


def __dir__():
    """The public names: ``__all__``, the extension module and the dunders."""
    dunders = {n for n in globals() if n.startswith("__") and n.endswith("__")}
    return sorted(set(__all__) | {"_v2ref"} | dunders)
