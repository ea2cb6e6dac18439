#!/usr/bin/env python3
"""Independent reference values of the differential-piston variance between
two circular apertures under von Karman turbulence (finite outer scale).

Regenerate with:  python3 tests/data/gen_vonkarman_piston.py > tests/data/vonkarman_piston.csv
Source: mpmath (arbitrary precision), mp.dps = 20; printed with 12 significant digits.

Method (pupil plane, not the spectral integral v2ref uses): the variance of the
difference of the pupil-averaged OPD of two apertures of diameter D a vector B apart is
    var = int T(rho) [D_opd(|rho + B|) - D_opd(rho)] d^2 rho,
T the autocorrelation of the uniform pupil normalised to unit integral,
T(rho) = (2/pi)(acos u - u sqrt(1-u^2)) / (pi D^2/4), u = rho/D, and D_opd the OPD
structure function of the von Karman spectrum Phi_phi(f) = C_Phi r0^(-5/3) (f^2 + L0^-2)^(-11/6)
(f in cycles/m), in closed form (Hankel transform
int_0^inf J0(b x) x (x^2 + a^2)^(-11/6) dx = (b/(2a))^(5/6) K_{5/6}(a b) / Gamma(11/6)):
    D_phi(r) = 4 pi C_Phi r0^(-5/3) [ (3/5) a^(-5/3) - (b/(2a))^(5/6) K_{5/6}(a b) / Gamma(11/6) ],
a = 1/L0, b = 2 pi r; D_opd = (lambda/(2 pi))^2 D_phi, r0 at lambda (the OPD does not depend
on lambda). Checks: the comment line "check" gives D_phi(1 m) at L0 = 1e7 m over the
Kolmogorov C_D (r/r0)^(5/3): 0.9931, the leading von Karman correction, which goes as
(r/L0)^(1/3) (the a^(-5/3) terms cancel exactly); and the variance of the Kolmogorov site
equals var_sf of tests/data/turbulence_reference.csv (389.16028093, an independent 2-D
quadrature). About 30 min on one busy core (the 8 m site is most of it).
Columns: site, seeing_arcsec, seeing_wavelength_um, aperture_m, baseline_m, outer_scale_m
(0: infinite), variance_um2.
"""
import mpmath as mp

mp.mp.dps = 20
pi = mp.pi
core = (mp.mpf(24) / 5 * mp.gamma(mp.mpf(6) / 5)) ** (mp.mpf(5) / 6)
CD = 2 * core
CPHI = mp.gamma(mp.mpf(11) / 6) ** 2 / (2 * pi ** (mp.mpf(11) / 3)) * core
ARCSEC = pi / 648000


def structure_opd(r, r0, lam, L0):
    """D_opd(r), um^2 (L0 = None: Kolmogorov)."""
    k2 = (lam / (2 * pi)) ** 2
    if L0 is None:
        return k2 * CD * (r / r0) ** (mp.mpf(5) / 3)
    if r == 0:
        return mp.mpf(0)
    a, b = 1 / L0, 2 * pi * r
    bracket = mp.mpf(3) / 5 * a ** (-mp.mpf(5) / 3) - (b / (2 * a)) ** (mp.mpf(5) / 6) * mp.besselk(
        mp.mpf(5) / 6, a * b
    ) / mp.gamma(mp.mpf(11) / 6)
    return k2 * 4 * pi * CPHI * r0 ** (-mp.mpf(5) / 3) * bracket


def variance(seeing, seeing_um, D, B, L0):
    lam = mp.mpf(seeing_um)
    r0 = lam * mp.mpf('1e-6') / (mp.mpf(seeing) * ARCSEC)
    D, B = mp.mpf(D), mp.mpf(B)
    area = pi * D * D / 4

    def T(rho):
        u = rho / D
        return (2 / pi) * (mp.acos(u) - u * mp.sqrt(1 - u * u)) / area

    S = lambda r: structure_opd(r, r0, lam, L0)

    def ring(rho):
        g = lambda th: S(mp.sqrt(rho * rho + B * B + 2 * rho * B * mp.cos(th))) - S(rho)
        return 2 * mp.quad(g, [0, pi / 2, pi])

    return mp.quad(lambda rho: rho * T(rho) * ring(rho), [0, D / 4, D / 2, 3 * D / 4, D])


SITES = [
    # name, seeing arcsec, at um, D m, B m, L0 m (None: infinite)
    ("paper_kolmogorov", '1', '2.2', '0.45', '18', None),
    ("paper_l0_25", '1', '2.2', '0.45', '18', mp.mpf(25)),
    ("readme_l0_25", '0.8', '0.5', '1.8', '40', mp.mpf(25)),
    ("large_l0_22", '0.8', '0.5', '8', '130', mp.mpf(22)),
]

print("# v2ref reference: two-aperture differential-piston variance, von Karman, pupil-plane quadrature")
print(f"# generator: python3 tests/data/gen_vonkarman_piston.py; mpmath {mp.__version__}; mp.dps = 20")
r0 = mp.mpf('2.2e-6') / ARCSEC
check = structure_opd(mp.mpf(1), r0, mp.mpf('2.2'), mp.mpf('1e7')) / structure_opd(mp.mpf(1), r0, mp.mpf('2.2'), None)
print(f"# check: von Karman / Kolmogorov structure function at r = 1 m, L0 = 1e7 m: {mp.nstr(check, 12)}")
print("# columns: site, seeing_arcsec, seeing_wavelength_um, aperture_m, baseline_m, outer_scale_m, variance_um2")
for name, seeing, at, D, B, L0 in SITES:
    v = variance(seeing, at, D, B, L0)
    l0 = 0 if L0 is None else L0
    print(f"{name},{seeing},{at},{D},{B},{mp.nstr(l0, 6)},{mp.nstr(v, 12)}")
