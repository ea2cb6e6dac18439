//! The one place a claim's status is decided: [`decide`], a function of
//! the ledger's printed value and rounding and of what the computation
//! found ([`Finding`]). Providers never name a status; they report numbers
//! (the exact value, the value of the paper's printed formula, the
//! independent checks of the exact value) or a computed predicate.

use super::{ClaimSpec, Status};
use crate::tolerance::MC_SIGMAS;

/// An independent confirmation of a computed value.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Check {
    /// A Monte Carlo estimate of the same quantity and its standard error:
    /// confirms a value within `tolerance::MC_SIGMAS` (5) standard errors.
    MonteCarlo {
        /// The Monte Carlo mean (or variance, or ratio).
        estimate: f64,
        /// Its standard error.
        stderr: f64,
    },
    /// The same quantity by a second, independent route (a closed form
    /// against a quadrature, a formula against an exact quadratic form):
    /// confirms a value within `tol`, absolute, in the claim's unit.
    Route {
        /// The value the other route gives.
        value: f64,
        /// The largest difference the two routes may show (a named
        /// tolerance of `crate::tolerance`, scaled to the value).
        tol: f64,
    },
}

impl Check {
    /// Whether this check confirms `x` (never for a non-finite `x`).
    pub fn confirms(&self, x: f64) -> bool {
        match *self {
            Check::MonteCarlo { estimate, stderr } => (x - estimate).abs() <= MC_SIGMAS * stderr,
            Check::Route { value, tol } => (x - value).abs() <= tol,
        }
    }

    /// `x`'s distance from the check, in standard errors (Monte Carlo) or
    /// in tolerances (route): for the notes.
    pub fn distance(&self, x: f64) -> f64 {
        match *self {
            Check::MonteCarlo { estimate, stderr } => (x - estimate) / stderr,
            Check::Route { value, tol } => (x - value) / tol,
        }
    }
}

/// What a provider computed for one claim: the numbers its status is
/// decided from.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Finding {
    /// A value in the ledger's unit.
    Number {
        /// The value this crate computes (the exact one, where the paper's
        /// formula is wrong).
        exact: f64,
        /// The value of the paper's printed formula or reading, where it
        /// differs in form from the exact computation.
        published: Option<f64>,
        /// Independent confirmations of `exact`.
        checks: Vec<Check>,
    },
    /// A threshold located on a Monte Carlo curve, with the interval its
    /// standard errors and the grid step allow.
    Interval {
        /// The located value.
        value: f64,
        /// Lower end of the interval.
        lo: f64,
        /// Upper end of the interval.
        hi: f64,
        /// False when the crossing lies outside the simulated range (the
        /// value is then the end of that range).
        resolved: bool,
    },
    /// A statement without a number, judged by a computed predicate.
    Statement {
        /// The evidence number shown in the table.
        value: Option<f64>,
        /// Whether the predicate holds.
        holds: bool,
    },
    /// The data it needs are not available.
    Unavailable,
    /// Its computation returned an error.
    Failed,
}

impl Finding {
    /// A number with neither a published formula nor a check.
    pub fn number(exact: f64) -> Finding {
        Finding::Number {
            exact,
            published: None,
            checks: Vec::new(),
        }
    }

    /// The value shown in the table's `computed` column.
    pub fn value(&self) -> Option<f64> {
        match self {
            Finding::Number { exact, .. } => Some(*exact),
            Finding::Interval { value, .. } => Some(*value),
            Finding::Statement { value, .. } => *value,
            Finding::Unavailable | Finding::Failed => None,
        }
    }
}

/// The status of the claim `spec` given what was computed.
///
/// * A check that does not confirm the exact value (or a non-finite one)
///   makes the claim `failed`: the computation is not trusted.
/// * A printed value: `reproduced` if the exact value is within the
///   rounding; otherwise `erratum` if the paper's printed formula is wrong
///   (its value is rejected by a check, or, without a check, lies outside
///   the rounding of the exact value) and the printed number follows that
///   formula (it is nearer the formula's value than the exact one);
///   otherwise `differs`.
/// * No printed value: `erratum` if the printed formula is wrong,
///   `qualitative` otherwise.
/// * A located threshold: `reproduced` if the crossing was resolved and
///   the printed value lies in its interval, `differs` otherwise.
/// * A statement: `qualitative` if its predicate holds, `differs` if not.
pub fn decide(spec: &ClaimSpec, finding: &Finding) -> Status {
    match finding {
        Finding::Failed => Status::Failed,
        Finding::Unavailable => Status::Unavailable,
        Finding::Statement { holds: true, .. } => Status::Qualitative,
        Finding::Statement { holds: false, .. } => Status::Differs,
        Finding::Interval {
            lo, hi, resolved, ..
        } => match spec.paper {
            Some(p) if *resolved && (*lo..=*hi).contains(&p) => Status::Reproduced,
            Some(_) => Status::Differs,
            None => Status::Failed,
        },
        Finding::Number {
            exact,
            published,
            checks,
        } => decide_number(spec, *exact, *published, checks),
    }
}

fn decide_number(spec: &ClaimSpec, exact: f64, published: Option<f64>, checks: &[Check]) -> Status {
    if !exact.is_finite() || !checks.iter().all(|c| c.confirms(exact)) {
        return Status::Failed;
    }
    let formula_wrong = published.is_some_and(|p| {
        if checks.is_empty() {
            spec.tol.is_some_and(|tol| (p - exact).abs() > tol)
        } else {
            checks.iter().any(|c| !c.confirms(p))
        }
    });
    match (spec.paper, spec.tol) {
        (Some(paper), Some(tol)) if (exact - paper).abs() <= tol => Status::Reproduced,
        (Some(paper), Some(_)) => {
            let follows_formula =
                published.is_some_and(|p| (p - paper).abs() < (exact - paper).abs());
            if formula_wrong && follows_formula {
                Status::Erratum
            } else {
                Status::Differs
            }
        }
        _ if formula_wrong => Status::Erratum,
        _ => Status::Qualitative,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(paper: Option<f64>, tol: Option<f64>) -> ClaimSpec {
        ClaimSpec {
            id: "test.claim".into(),
            section: String::new(),
            kind: String::new(),
            unit: String::new(),
            statement: String::new(),
            paper,
            tol,
        }
    }

    fn number(exact: f64, published: Option<f64>, checks: Vec<Check>) -> Finding {
        Finding::Number {
            exact,
            published,
            checks,
        }
    }

    /// A planted 1 % error moves a reproduced value out of a rounding
    /// finer than 1 %, and breaks a Monte Carlo check resolving 0.1 %.
    #[test]
    fn a_planted_one_percent_error_changes_the_status() {
        let printed = spec(Some(1.2337), Some(5e-5));
        let exact = 1.233_701;
        assert_eq!(
            decide(&printed, &Finding::number(exact)),
            Status::Reproduced
        );
        assert_eq!(
            decide(&printed, &Finding::number(exact * 1.01)),
            Status::Differs
        );
        let mc = Check::MonteCarlo {
            estimate: 100.0,
            stderr: 0.1,
        };
        let free = spec(None, None);
        assert_eq!(
            decide(&free, &number(100.2, None, vec![mc])),
            Status::Qualitative
        );
        assert_eq!(
            decide(&free, &number(101.0, None, vec![mc])),
            Status::Failed
        );
    }

    /// Erratum needs the printed number to follow a formula the checks
    /// reject: an exact value made equal to the printed one is reproduced,
    /// a published formula equal to the exact value leaves `differs`.
    #[test]
    fn an_erratum_needs_a_wrong_formula_the_printed_number_follows() {
        let printed = spec(Some(0.54), Some(0.005));
        let (exact, published) = (1.0196, 0.5390);
        assert_eq!(
            decide(&printed, &number(exact, Some(published), vec![])),
            Status::Erratum
        );
        assert_eq!(
            decide(&printed, &number(0.54, Some(published), vec![])),
            Status::Reproduced
        );
        assert_eq!(
            decide(&printed, &number(exact, Some(exact), vec![])),
            Status::Differs
        );
        assert_eq!(decide(&printed, &Finding::number(exact)), Status::Differs);
        // The printed number nearer the exact value than the formula's.
        assert_eq!(
            decide(&printed, &number(0.56, Some(2.0), vec![])),
            Status::Differs
        );
        // Without a printed number: the checks decide.
        let mc = Check::MonteCarlo {
            estimate: 24019.8,
            stderr: 20.8,
        };
        let free = spec(None, None);
        assert_eq!(
            decide(&free, &number(24020.0, Some(210820.0), vec![mc])),
            Status::Erratum
        );
        assert_eq!(
            decide(&free, &number(24020.0, Some(24030.0), vec![mc])),
            Status::Qualitative
        );
    }

    #[test]
    fn failures_intervals_and_predicates() {
        let printed = spec(Some(300.0), Some(5.0));
        let route = Check::Route {
            value: 1.0,
            tol: 1e-10,
        };
        assert_eq!(decide(&printed, &Finding::Failed), Status::Failed);
        assert_eq!(decide(&printed, &Finding::number(f64::NAN)), Status::Failed);
        assert_eq!(
            decide(&spec(None, None), &number(1.0 + 1e-9, None, vec![route])),
            Status::Failed
        );
        let interval = |lo, hi, resolved| Finding::Interval {
            value: 0.5 * (lo + hi),
            lo,
            hi,
            resolved,
        };
        assert_eq!(
            decide(&printed, &interval(250.0, 350.0, true)),
            Status::Reproduced
        );
        assert_eq!(
            decide(&printed, &interval(250.0, 350.0, false)),
            Status::Differs
        );
        assert_eq!(
            decide(&printed, &interval(310.0, 350.0, true)),
            Status::Differs
        );
        let statement = |holds| Finding::Statement { value: None, holds };
        assert_eq!(decide(&printed, &statement(true)), Status::Qualitative);
        assert_eq!(decide(&printed, &statement(false)), Status::Differs);
        assert_eq!(decide(&printed, &Finding::Unavailable), Status::Unavailable);
    }
}
