//! Claims of the moments of one sample, printed against exact, by Monte
//! Carlo: `appendix.gaussian_moments`, `appendix.photon_moments`,
//! `snr.combined_noise_variance`.

use super::*;

/// The moments of one sample, printed vs exact, by Monte Carlo:
/// `appendix.gaussian_moments`, `appendix.photon_moments` (m = c = n, sample
/// 0 of the Appendix case), `snr.combined_noise_variance`.
pub(super) fn sample_moment_claims(
    _find: &Find<'_>,
    case: &Case,
    sz: &Sizes,
) -> Result<Vec<Computed>> {
    let (m, s) = (10.0, 2.0);
    let gauss = NoiseModel {
        read_noise: s,
        photon: false,
    };
    let mc = sample_moments(
        m,
        0.0,
        &gauss,
        sz.scalar,
        seed("appendix.gaussian_moments"),
        0,
    )?;
    let p4 = published::gaussian_m4(m, s);
    let p2 = published::gaussian_m2(m, s);
    let e = moments(&gauss, m, 0.0).expect("a finite sample");
    let same = |x: f64, y: f64| (x - y).abs() <= IDENTITY_REL * y.abs();
    // The predicate: the printed forms are the exact cumulant forms, and
    // the Monte Carlo confirms them.
    let printed_exact = same(p4, e.raw[4]) && same(p2, e.raw[2]);
    let holds = printed_exact
        && self::mc(mc[3].mean, mc[3].stderr_mean()).confirms(p4)
        && self::mc(mc[1].mean, mc[1].stderr_mean()).confirms(p2);
    let gaussian = Computed::statement(
        "appendix.gaussian_moments",
        Some(mc[3].mean / p4),
        holds,
        format!(
                "printed forms equal to the exact cumulant forms: {printed_exact} ({p4} and {}, {p2} and {}); Monte Carlo m = {m}, s = {s}, {} draws: <M^4> = {}, <M^2> = {}",
                e.raw[4],
                e.raw[2],
                sz.scalar,
                versus(mc[3].mean, mc[3].stderr_mean(), p4),
                versus(mc[1].mean, mc[1].stderr_mean(), p2),
            ),
    );
    Ok(vec![
        gaussian,
        photon_moment_claim(case, sz)?,
        combined_noise_claim(case, s, sz)?,
    ])
}

fn photon_moment_claim(case: &Case, sz: &Sizes) -> Result<Computed> {
    // Photon: c = 10, m = 10, n = 20 (sample 0 of the Appendix case).
    let n = case.setup.photons;
    let (mp, cp) = (n, n);
    let nn = mp + cp;
    let mc = sample_moments(
        mp,
        cp,
        &case.photon,
        sz.scalar,
        seed("appendix.photon_moments"),
        0,
    )?;
    let e = moments(&case.photon, mp, nn).expect("a finite sample");
    let p4 = published::photon_m4(nn);
    let p2 = published::photon_m2(nn);
    Ok(Computed::formula(
        "appendix.photon_moments",
        e.raw[4],
        p4,
        format!(
                "the printed n^4+6n^3+7n^2+n and n^2+n are the raw moments of the Poisson count I (mean n), not of M = I - c. Exact for M = m + e (cumulants of e all equal n): <M^2> = m^2 + n, <M^4> = m^4 + 6m^2 n + 4mn + n + 3n^2. At m = c = {mp} (n = {nn}), {} draws: <M^4> = {} (printed {p4}, {:.0} se away); <M^2> = {} (printed {p2})",
                sz.scalar,
                versus(mc[3].mean, mc[3].stderr_mean(), e.raw[4]),
                (mc[3].mean - p4) / mc[3].stderr_mean(),
                versus(mc[1].mean, mc[1].stderr_mean(), e.raw[2]),
            ),
    )
    .checked(self::mc(mc[3].mean, mc[3].stderr_mean())))
}

fn combined_noise_claim(case: &Case, s: f64, sz: &Sizes) -> Result<Computed> {
    // Combined noise: var(M^2) with both vs the sum of each alone.
    let n = case.setup.photons;
    let (mp, cp) = (n, n);
    let nn = mp + cp;
    let gauss = NoiseModel {
        read_noise: s,
        photon: false,
    };
    let both = NoiseModel {
        read_noise: s,
        photon: true,
    };
    let mc = sample_moments(
        mp,
        cp,
        &both,
        sz.scalar,
        seed("snr.combined_noise_variance"),
        0,
    )?;
    let exact = var_m2(&both, mp, nn);
    let sum = var_m2(&gauss, mp, nn) + var_m2(&case.photon, mp, nn);
    // var(M^2) by Monte Carlo, from the moments of M^2 (sample 2 of mc).
    let v = mc[1].variance();
    let se = mc[1].stderr_variance();
    Ok(Computed::formula(
        "snr.combined_noise_variance",
        exact,
        sum,
        format!(
                "var(M^2) with both noises is not the sum of the two: the 2 kappa2^2 term of var(M^2) = 4m^2 k2 + 4m k3 + k4 + 2 k2^2 with k2 = s^2 + n adds the cross term 4 s^2 n. At m = c = {mp}, n = {nn}, s = {s}: exact {exact}, sum of the parts {sum}; Monte Carlo ({} draws) var(M^2) = {} ({:.1} se from the sum). The paper's photon part is itself the erratum of appendix.photon_variances",
                sz.scalar,
                versus(v, se, exact),
                (v - sum) / se,
            ),
    )
    .checked(self::mc(v, se)))
}
