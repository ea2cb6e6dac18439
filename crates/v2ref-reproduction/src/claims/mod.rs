//! The claims ledger: every quantitative statement of the paper
//! (`claims.toml` at this crate's root, inside its package, a copy of the
//! shared ledger with the same ids and printed values), computed by this
//! crate and given a status.
//!
//! Each area of the paper has its own provider module returning the claims
//! it computes; [`evaluate`] merges them with the ledger, and any claim no
//! provider answers is `pending`.

use crate::cases::Effort;
use serde::{Deserialize, Serialize};

mod bias;
mod foundation;
mod noise;
mod piston;
mod verdict;

pub use piston::sensitivity;
pub use verdict::{decide, Check, Finding};

/// The ledger as shipped in the crate.
pub const LEDGER_TOML: &str = include_str!("../../claims.toml");

/// One entry of the ledger.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
pub struct ClaimSpec {
    /// Stable id, `area.name`.
    pub id: String,
    /// The paper's section.
    pub section: String,
    /// closed-form | numerical | monte-carlo | qualitative.
    pub kind: String,
    /// Unit of `paper` and of the computed value.
    pub unit: String,
    /// Paraphrase of the statement.
    pub statement: String,
    /// The printed number, where there is one.
    pub paper: Option<f64>,
    /// Half-width of the paper's rounding, absolute, in `unit`.
    pub tol: Option<f64>,
}

#[derive(Deserialize)]
struct Ledger {
    claim: Vec<ClaimSpec>,
}

/// Parses the ledger shipped with the crate.
pub fn ledger() -> Vec<ClaimSpec> {
    // The ledger is a compile-time constant checked by a test; a parse
    // failure is a build defect, not user input.
    toml::from_str::<Ledger>(LEDGER_TOML)
        .expect("the claims ledger (claims.toml) is valid")
        .claim
}

/// A claim's verdict (listed in the header of this crate's `claims.toml`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Status {
    /// Computed, within the paper's rounding.
    Reproduced,
    /// Computed, outside the rounding; the note says why.
    Differs,
    /// The paper's statement is wrong; the note gives the right value.
    Erratum,
    /// A statement without a number; the note gives the computed evidence.
    Qualitative,
    /// Needs data the project cannot have; the note says which.
    Unavailable,
    /// Its computation failed; the note carries the error.
    Failed,
    /// Not computed yet.
    Pending,
}

impl Status {
    /// The lowercase name.
    pub fn as_str(&self) -> &'static str {
        match self {
            Status::Reproduced => "reproduced",
            Status::Differs => "differs",
            Status::Erratum => "erratum",
            Status::Qualitative => "qualitative",
            Status::Unavailable => "unavailable",
            Status::Failed => "failed",
            Status::Pending => "pending",
        }
    }
}

/// What a provider computed for one claim: the numbers its status is
/// decided from ([`decide`]) and the evidence in words.
#[derive(Debug, Clone, PartialEq)]
pub struct Computed {
    /// The ledger id.
    pub id: &'static str,
    /// The numbers (or the predicate) the status is decided from.
    pub finding: Finding,
    /// The evidence, in words and computed numbers.
    pub note: String,
}

impl Computed {
    /// A value in the ledger's unit, with neither a printed formula nor a
    /// check: judged against the printed value and its rounding.
    pub fn number(id: &'static str, exact: f64, note: impl Into<String>) -> Computed {
        Computed {
            id,
            finding: Finding::number(exact),
            note: note.into(),
        }
    }

    /// The exact value and the value of the paper's printed formula (or
    /// reading), `published`.
    pub fn formula(
        id: &'static str,
        exact: f64,
        published: f64,
        note: impl Into<String>,
    ) -> Computed {
        Computed {
            id,
            finding: Finding::Number {
                exact,
                published: Some(published),
                checks: Vec::new(),
            },
            note: note.into(),
        }
    }

    /// This value, confirmed by `check` as well (a no-op on a finding
    /// that is not a number).
    pub fn checked(mut self, check: Check) -> Computed {
        if let Finding::Number { checks, .. } = &mut self.finding {
            checks.push(check);
        }
        self
    }

    /// A statement judged by a computed predicate, `holds`, with its
    /// evidence number `value`.
    pub fn statement(
        id: &'static str,
        value: Option<f64>,
        holds: bool,
        note: impl Into<String>,
    ) -> Computed {
        Computed {
            id,
            finding: Finding::Statement { value, holds },
            note: note.into(),
        }
    }

    /// A claim needing data the project does not have; the note says which.
    pub fn unavailable(id: &'static str, note: impl Into<String>) -> Computed {
        Computed {
            id,
            finding: Finding::Unavailable,
            note: note.into(),
        }
    }

    /// A claim whose computation failed with `error`: status
    /// [`Status::Failed`], the error in the note (never silently `pending`).
    pub fn failed(id: &'static str, error: &crate::Error) -> Computed {
        Computed {
            id,
            finding: Finding::Failed,
            note: format!("computation failed: {error}"),
        }
    }
}

/// The claims of one step of a provider: what it `computed`, or, if the
/// step failed, [`Computed::failed`] for each of its claim `ids` (a failure
/// is reported, never left `pending`).
pub(super) fn settle(
    ids: &[&'static str],
    computed: crate::Result<Vec<Computed>>,
) -> Vec<Computed> {
    match computed {
        Ok(claims) => claims,
        Err(err) => ids.iter().map(|id| Computed::failed(id, &err)).collect(),
    }
}

/// One row of the `claims` answer (the CLI contract's fields).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct ClaimResult {
    /// Ledger id.
    pub id: String,
    /// The paper's printed value.
    pub paper: Option<f64>,
    /// The computed value.
    pub computed: Option<f64>,
    /// Unit.
    pub unit: String,
    /// Verdict.
    pub status: Status,
    /// Evidence.
    pub note: String,
    /// Value from the formula as printed (errata only).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub published: Option<f64>,
    /// Correct value (errata only).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub exact: Option<f64>,
}

/// What every provider computed, in no particular order (one entry per
/// claim a provider answers). [`evaluate`] judges them with [`decide`].
pub fn compute(effort: Effort) -> Vec<Computed> {
    let specs = ledger();
    let find = |id: &str| specs.iter().find(|s| s.id == id);
    // The four areas side by side: independent, each deterministic.
    let ((foundation, noise), (bias, piston)) = rayon::join(
        || {
            rayon::join(
                || foundation::claims(&find),
                || noise::claims(&find, effort),
            )
        },
        || {
            rayon::join(
                || bias::claims(&find, effort),
                || piston::claims(&find, effort),
            )
        },
    );
    [foundation, noise, bias, piston].concat()
}

/// Computes every claim of the ledger and decides its status, in ledger
/// order.
pub fn evaluate(effort: Effort) -> Vec<ClaimResult> {
    judge(&ledger(), &compute(effort))
}

/// The table row of each claim of `specs` from what was `computed`: the
/// status from [`decide`], `pending` where no provider answered.
pub fn judge(specs: &[ClaimSpec], computed: &[Computed]) -> Vec<ClaimResult> {
    specs
        .iter()
        .map(|spec| {
            let c = computed.iter().find(|c| c.id == spec.id);
            let (published, exact) = match c.map(|c| &c.finding) {
                Some(Finding::Number {
                    exact,
                    published: Some(p),
                    ..
                }) => (Some(*p), Some(*exact)),
                _ => (None, None),
            };
            ClaimResult {
                id: spec.id.clone(),
                paper: spec.paper,
                computed: c.and_then(|c| c.finding.value()),
                unit: spec.unit.clone(),
                status: c.map_or(Status::Pending, |c| decide(spec, &c.finding)),
                note: c.map_or_else(
                    || "not computed yet: the issue that computes it is open".to_owned(),
                    |c| c.note.clone(),
                ),
                published,
                exact,
            }
        })
        .collect()
}

/// `lo-hi um`, the wavelengths of the support of `spectrum` (held in
/// wavenumber, µm⁻¹) to the 0.1 µm the notes show.
fn band_text(spectrum: &crate::formalism::spectrum::Spectrum) -> String {
    let (lo_per_um, hi_per_um) = spectrum.support();
    format!("{:.1}-{:.1} um", 1.0 / hi_per_um, 1.0 / lo_per_um)
}

/// Looks a spec up by id; providers receive one of these.
pub type Find<'a> = dyn Fn(&str) -> Option<&'a ClaimSpec> + 'a;

/// The claims table as Markdown: one row per claim with the paper's value,
/// the computed value, the unit, the status and the evidence.
pub fn to_markdown(results: &[ClaimResult]) -> String {
    let fmt = |v: Option<f64>| v.map_or_else(|| "–".to_owned(), |x| format!("{x:.6}"));
    let mut out = String::from(
        "| claim | paper | computed | unit | status | evidence |\n|---|---:|---:|---|---|---|\n",
    );
    for r in results {
        let mut note = r.note.replace('|', "\\|").replace('\n', " ");
        if let (Some(p), Some(e)) = (r.published, r.exact) {
            note = format!("published formula: {p:.6}; exact: {e:.6}. {note}");
        }
        out.push_str(&format!(
            "| `{}` | {} | {} | {} | {} | {} |\n",
            r.id,
            fmt(r.paper),
            fmt(r.computed),
            r.unit,
            r.status.as_str(),
            note
        ));
    }
    out
}

/// How many claims have each status, in the order of [`Status`].
pub fn status_counts(results: &[ClaimResult]) -> Vec<(Status, usize)> {
    [
        Status::Reproduced,
        Status::Differs,
        Status::Erratum,
        Status::Qualitative,
        Status::Unavailable,
        Status::Failed,
        Status::Pending,
    ]
    .into_iter()
    .map(|s| (s, results.iter().filter(|r| r.status == s).count()))
    .collect()
}

/// The counts of `results` in words, in the order of [`Status`] (a status
/// no claim has is left out): the sentence README.md states, checked
/// against the committed reproduction by the test suite.
pub fn summary(results: &[ClaimResult]) -> String {
    status_counts(results)
        .into_iter()
        .filter(|&(_, n)| n > 0)
        .map(|(status, n)| match status {
            Status::Differs => format!("{n} differing (with the reason)"),
            Status::Erratum => format!("{n} errata (with the right value and the evidence)"),
            Status::Qualitative => format!("{n} qualitative statements with computed evidence"),
            other => format!("{n} {}", other.as_str()),
        })
        .collect::<Vec<_>>()
        .join(", ")
}
