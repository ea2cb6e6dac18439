#!/usr/bin/env python3
"""Independent reference values for v2ref's Fresnel integrals C(x), S(x).

Regenerate with:  python3 tests/data/gen_fresnel_reference.py > tests/data/fresnel_reference.csv
Source: mpmath (arbitrary precision) fresnelc / fresnels, working precision
50 decimal digits, normalization C(x) = int_0^x cos(pi t^2 / 2) dt,
S(x) = int_0^x sin(pi t^2 / 2) dt; values printed with 17 significant digits.
Grid: x = 0 to 12 in steps of 0.0731 (no grid point on the method switch at
1.5), points on both sides of the switch, tiny and large arguments (x = 1000.1
and 12345.678, whose x² is not a float: the phase πx²/2 needs its rounding
error), and
negative arguments (both functions are odd).
Also: V2 of a point source in a flat band under quadratic dispersion of
peak-to-peak phase P, |int_{-1}^{1} exp(i P u^2) du / 2|, by direct mpmath
quadrature (mpmath.quad) — an independent check of the closed form
(C(T)^2 + S(T)^2) / T^2 with T = sqrt(2P/pi).
"""
import mpmath

mpmath.mp.dps = 50

xs = [k * 0.0731 for k in range(0, 165)]
xs += [1e-10, 1e-5, 1e-3, 0.1, 1.4999, 1.5, 1.5001, 2.0, 3.0, 5.0, 20.0, 50.0, 100.0, 1000.0, 1000.1, 12345.678]
xs += [-0.3, -1.2, -1.7, -4.0]
xs = sorted(set(xs))

def g(v):
    return mpmath.nstr(v, 17, min_fixed=-1, max_fixed=1)

print("# v2ref reference: Fresnel integrals C(x), S(x) (pi/2 normalization)")
print(f"# generator: python3 tests/data/gen_fresnel_reference.py; mpmath {mpmath.__version__}; mp.dps = 50")
print("# columns: kind (value|v2point), x or peak-to-peak phase P [rad], C(x) or V2^2, S(x) or empty")
for x in xs:
    mx = mpmath.mpf(x)  # the exact binary value the f64 x holds (not repr(x), a decimal)
    print(f"value,{x!r},{g(mpmath.fresnelc(mx))},{g(mpmath.fresnels(mx))}")
for p in [0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0, 10.0]:
    mp = mpmath.mpf(p)
    re = mpmath.quad(lambda u: mpmath.cos(mp * u * u), [-1, 0, 1]) / 2
    im = mpmath.quad(lambda u: mpmath.sin(mp * u * u), [-1, 0, 1]) / 2
    print(f"v2point,{p!r},{g(re * re + im * im)},")
