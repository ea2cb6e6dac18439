#!/usr/bin/env python3
"""Independent reference values for v2ref's turbulence module.

Regenerate with:  python3 tests/data/gen_turbulence_reference.py > tests/data/turbulence_reference.csv
Source: mpmath (arbitrary precision), mp.dps = 30; printed with 17 significant digits.
Quantities:
- C_D = 2 (24/5 Gamma(6/5))^(5/6)           (Kolmogorov phase structure function coefficient)
- C_Phi = Gamma(11/6)^2/(2 pi^(11/3)) (24/5 Gamma(6/5))^(5/6)  (phase power spectrum coefficient)
- I(a) = int_{-inf}^{inf} (1+u^2)^(-a) du computed by quadrature (not by the Gamma formula),
  for a = 11/6, 10/3, 0.75, 0.875
- G(fx) = int_{-inf}^{inf} Phi_opd(sqrt(fx^2+fy^2)) [2 J1(pi D f)/(pi D f)]^2 dfy, by quadrature,
  for r0 = 2.2e-6 / (pi/648000) m (1 arcsec at 2.2 um), lambda = 2.2 um, D = 0.45 m, Kolmogorov.
- var_sf: the differential piston variance for B = 18 m from the aperture-averaged structure
  function, int T(rho) [D(|rho+B|) - D(rho)] d^2 rho, by 2-D quadrature (pupil plane).
Units: G in um^2 m, variance in um^2.
"""
import mpmath as mp

mp.mp.dps = 30
pi = mp.pi
core = (mp.mpf(24) / 5 * mp.gamma(mp.mpf(6) / 5)) ** (mp.mpf(5) / 6)
CD = 2 * core
CPHI = mp.gamma(mp.mpf(11) / 6) ** 2 / (2 * pi ** (mp.mpf(11) / 3)) * core

lam = mp.mpf('2.2')  # um
r0 = mp.mpf('2.2e-6') / (pi / 648000)
D = mp.mpf('0.45')
B = mp.mpf(18)
K = (lam / (2 * pi)) ** 2 * CPHI * r0 ** (-mp.mpf(5) / 3)


def jinc(z):
    return mp.mpf(1) if z == 0 else 2 * mp.besselj(1, z) / z


def G(fx):
    def f(fy):
        r = mp.sqrt(fx * fx + fy * fy)
        return K * r ** (-mp.mpf(11) / 3) * jinc(pi * D * r) ** 2
    # split at fx, then at every half period of the Bessel oscillation up to 400/D
    pts = [mp.mpf(0), fx]
    x = fx
    while x < 40 / D:
        x = x * 2 if x < 1 / D else x + mp.mpf(1) / (2 * D)
        pts.append(x)
    body = mp.quad(f, pts)
    tail = mp.quad(f, [pts[-1], mp.inf])
    return 2 * (body + tail)


def I(a):
    return mp.quad(lambda u: (1 + u * u) ** (-a), [-mp.inf, 0, mp.inf])


def var_sf():
    area = pi * D * D / 4
    def T(rho):
        u = rho / D
        return (2 / pi) * (mp.acos(u) - u * mp.sqrt(1 - u * u)) / area
    def S(r):
        return (lam / (2 * pi)) ** 2 * CD * (r / r0) ** (mp.mpf(5) / 3)
    def ring(rho):
        g = lambda th: S(mp.sqrt(rho * rho + B * B + 2 * rho * B * mp.cos(th))) - S(rho)
        return 2 * mp.quad(g, [0, pi / 2, pi])
    return mp.quad(lambda rho: rho * T(rho) * ring(rho), [0, D / 4, D / 2, 3 * D / 4, D])


print("# v2ref reference: Kolmogorov constants, profile integrals, transverse integral G, piston variance")
print(f"# generator: python3 tests/data/gen_turbulence_reference.py; mpmath {mp.__version__}; mp.dps = 30")
print("# columns: name, argument, value")
s = lambda v: mp.nstr(v, 17)
print(f"C_D,0,{s(CD)}")
print(f"C_Phi,0,{s(CPHI)}")
print(f"I,{s(mp.mpf(11)/6)},{s(I(mp.mpf(11)/6))}")
print(f"I,{s(mp.mpf(10)/3)},{s(I(mp.mpf(10)/3))}")
# a < 1: Gamma(a - 1/2) with a - 1/2 < 1/2, near the pole of the crate's
# Gamma at 0 (exact binary arguments; the quadrature of the slow
# u^(-2a) tail agrees with the Gamma formula to 1e-17 here, to 2e-9 only
# at a = 0.625, which is therefore not used)
for a in ['0.75', '0.875']:
    print(f"I,{a},{s(I(mp.mpf(a)))}")
for fxd in ['0.001', '0.1', '1', '3']:
    fx = mp.mpf(fxd) / D
    print(f"G,{s(fx)},{s(G(fx))}")
print(f"var_sf,18,{s(var_sf())}")
