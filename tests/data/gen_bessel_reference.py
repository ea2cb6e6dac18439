#!/usr/bin/env python3
"""Independent reference values for v2ref's Bessel functions.

Regenerate with:  python3 tests/data/gen_bessel_reference.py > tests/data/bessel_reference.csv
Source: mpmath (arbitrary precision), working precision 50 decimal digits;
values printed with 17 significant digits (exact to the last f64 ulp).
Grid: x = 0 to 100 in steps of 0.37 (an irrational-looking step, so that
no grid point sits on a zero or on a method switch), plus points near the
recurrence/asymptotic switch at 30, the series/ratio switch of jinc at 4
and tiny arguments (down to 1e-300, where Miller's recurrence must rescale).
Zeros: the first 30 positive zeros of J1 (mpmath.besseljzero(1, s)).
"""
import mpmath

mpmath.mp.dps = 50

xs = [k * 0.37 for k in range(0, 271)]
xs += [1e-300, 1e-100, 1e-30, 1e-12, 1e-8, 1e-6, 9.9e-6, 1e-4, 0.5, 3.8, 3.999, 4.0, 4.001, 29.999, 30.0, 30.001, 29.5, 30.5, 55.0, 99.99]
xs = sorted(set(xs))

print("# v2ref reference: Bessel J0, J1 and jinc = 2 J1(x)/x")
print(f"# generator: python3 tests/data/gen_bessel_reference.py; mpmath {mpmath.__version__}; mp.dps = 50")
print("# columns: kind (value|zero), x or zero index s, J0(x), J1(x), jinc(x) (value rows); zero (zero rows)")
for x in xs:
    mx = mpmath.mpf(x)  # the exact binary value the f64 x holds (not repr(x), a decimal)
    j0 = mpmath.besselj(0, mx)
    j1 = mpmath.besselj(1, mx)
    jinc = mpmath.mpf(1) if mx == 0 else 2 * j1 / mx
    print(f"value,{x!r},{mpmath.nstr(j0, 17, min_fixed=-1, max_fixed=1)},"
          f"{mpmath.nstr(j1, 17, min_fixed=-1, max_fixed=1)},"
          f"{mpmath.nstr(jinc, 17, min_fixed=-1, max_fixed=1)}")
for s in range(1, 31):
    z = mpmath.besseljzero(1, s)
    print(f"zero,{s},{mpmath.nstr(z, 20)},,")
