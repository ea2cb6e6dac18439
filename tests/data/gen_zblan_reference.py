#!/usr/bin/env python3
"""Independent reference values for v2ref's refractive index of ZBLAN and
the dispersion of a length of it.

Regenerate with:  python3 tests/data/gen_zblan_reference.py > tests/data/zblan_reference.csv
Source: the two-term Sellmeier formula of F. Gan, "Optical properties of
fluoride glasses: a review", J. Non-Cryst. Solids 184, 9-20 (1995), as
tabulated by refractiveindex.info (glass/misc/ZBLAN/nk/Gan.yml),
n^2 = 1 + B1 l^2/(l^2 - C1^2) + B2 l^2/(l^2 - C2^2), l in um, written here
in the wavelength form the source gives (v2ref evaluates it from the
wavenumber), in mpmath at 50 decimal digits; 17 significant digits printed.
Sanity: n = 1.5010 at the sodium D line (0.5893 um), against the n_d of
about 1.50 quoted for ZBLAN.
Also (kind p2p): the quadratic peak-to-peak phase P = |D|/2 (Delta sigma/2)^2
of L = x um of ZBLAN over the flat 2.0-2.4 um band, D = d^2/dsigma^2 of
2 pi sigma n(sigma) L at the band centre sigma0 = (1/2.4 + 1/2.0)/2 1/um,
differentiated by mpmath.diff (analytic function, 50 digits).
"""
import mpmath

mpmath.mp.dps = 50
B1, C1 = mpmath.mpf("1.22514"), mpmath.mpf("0.08969")
B2, C2 = mpmath.mpf("1.52898"), mpmath.mpf("21.3825")

print("# v2ref reference: refractive index of ZBLAN (Gan 1995 Sellmeier) and its quadratic dispersion over 2.0-2.4 um")
print(f"# generator: python3 tests/data/gen_zblan_reference.py; mpmath {mpmath.__version__}; mp.dps = 50")
print("kind,x,value")


def index(lam):
    l2 = lam**2
    return mpmath.sqrt(1 + B1 * l2 / (l2 - C1**2) + B2 * l2 / (l2 - C2**2))


for lam in ["0.5893", "1.0", "1.55", "2.0", "2.2", "2.4", "3.0", "3.5"]:
    print(f"n,{lam},{mpmath.nstr(index(mpmath.mpf(lam)), 17)}")
lo, hi = 1 / mpmath.mpf("2.4"), 1 / mpmath.mpf("2.0")
for length in ["10000", "25000"]:
    L = mpmath.mpf(length)
    d = mpmath.diff(lambda s: 2 * mpmath.pi * s * index(1 / s) * L, (lo + hi) / 2, 2)
    p = abs(d) / 2 * ((hi - lo) / 2) ** 2
    print(f"p2p,{length},{mpmath.nstr(p, 17)}")
