#!/usr/bin/env python3
"""Independent reference values for v2ref's refractive index of ZBLAN.

Regenerate with:  python3 tests/data/gen_zblan_reference.py > tests/data/zblan_reference.csv
Source: the two-term Sellmeier formula of F. Gan, "Optical properties of
fluoride glasses: a review", J. Non-Cryst. Solids 184, 9-20 (1995), as
tabulated by refractiveindex.info (glass/misc/ZBLAN/nk/Gan.yml),
n^2 = 1 + B1 l^2/(l^2 - C1^2) + B2 l^2/(l^2 - C2^2), l in um, written here
in the wavelength form the source gives (v2ref evaluates it from the
wavenumber), in mpmath at 50 decimal digits; 17 significant digits printed.
Sanity: n = 1.5010 at the sodium D line (0.5893 um), against the n_d of
about 1.50 quoted for ZBLAN.
"""
import mpmath

mpmath.mp.dps = 50
B1, C1 = mpmath.mpf("1.22514"), mpmath.mpf("0.08969")
B2, C2 = mpmath.mpf("1.52898"), mpmath.mpf("21.3825")

print("# v2ref reference: refractive index of ZBLAN (Gan 1995 Sellmeier)")
print(f"# generator: python3 tests/data/gen_zblan_reference.py; mpmath {mpmath.__version__}; mp.dps = 50")
print("wavelength_um,n")
for lam in ["0.5893", "1.0", "1.55", "2.0", "2.2", "2.4", "3.0", "3.5"]:
    l2 = mpmath.mpf(lam) ** 2
    n = mpmath.sqrt(1 + B1 * l2 / (l2 - C1**2) + B2 * l2 / (l2 - C2**2))
    print(f"{lam},{mpmath.nstr(n, 17)}")
