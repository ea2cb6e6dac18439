//! Compact summaries of the bias studies as insta snapshots, so that a
//! reviewer sees any drift of a maximum, a threshold or a claim in the diff.

use serde::Serialize;
use std::path::Path;
use v2ref_core::tolerance::{GOLDEN_ABS, GOLDEN_REL};
use v2ref_reproduction::cases::Effort;
use v2ref_reproduction::table::Table;

/// Six significant digits: enough to see drift, stable across platforms.
fn sig(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let p = 5 - x.abs().log10().floor() as i32;
    let m = 10f64.powi(p);
    (x * m).round() / m
}

fn golden(name: &str) -> Table {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join(format!("{name}.csv"));
    Table::from_csv(name, &std::fs::read_to_string(path).unwrap()).unwrap()
}

#[derive(Serialize)]
struct Extremum {
    column: String,
    max_abs: f64,
    at: f64,
}

fn extrema(t: &Table, skip: usize) -> Vec<Extremum> {
    let x = t.column(&t.columns[0].name).unwrap();
    t.columns[skip..]
        .iter()
        .map(|c| {
            let y = t.column(&c.name).unwrap();
            let (i, m) = y.iter().enumerate().fold((0, 0.0_f64), |(bi, bm), (i, v)| {
                if v.abs() > bm {
                    (i, v.abs())
                } else {
                    (bi, bm)
                }
            });
            Extremum {
                column: c.name.clone(),
                max_abs: sig(m),
                at: sig(x[i]),
            }
        })
        .collect()
}

/// The bias figures (0–3) recomputed by the library on the Quick grids
/// (every 5th point of Figs. 1–2, every 4th of Fig. 3; Fig. 0 whole), so
/// that this test runs the numeric code rather than reading back the
/// committed CSVs (issue 16): each recomputed point must equal the golden
/// one at the same abscissa to the golden tolerance, and the extrema and
/// thresholds of the recomputed curves are snapshotted for review.
#[test]
#[ignore = "slow tier: every figure's extrema (8 s)"]
fn figure_extrema() {
    let figures = v2ref_reproduction::figures::all(Effort::Quick).unwrap();
    let computed = |name: &str| -> Table {
        figures
            .iter()
            .flat_map(|f| &f.tables)
            .find(|t| t.name == name)
            .unwrap_or_else(|| panic!("table {name} not computed"))
            .clone()
    };
    let mut compared = 0;
    for fig in figures
        .iter()
        .filter(|f| ["fig0", "fig1", "fig2", "fig3"].contains(&f.id.as_str()))
    {
        for t in &fig.tables {
            compared += agrees_with_golden(t, &golden(&t.name));
        }
    }
    assert!(compared > 2000, "{compared} points compared");

    let fig0 = computed("fig0_normalization");
    let strokes = fig0.column("stroke").unwrap();
    let thresholds: Vec<(String, Option<f64>)> = fig0.columns[2..]
        .iter()
        .map(|c| {
            let d = fig0.column(&c.name).unwrap();
            (
                c.name.clone(),
                v2ref_core::bias::normalization::threshold_stroke(&strokes, &d, 0.002).map(sig),
            )
        })
        .collect();
    insta::assert_json_snapshot!("fig0_thresholds_0p2pct_um", thresholds);
    insta::assert_json_snapshot!("fig1_v1_extrema", extrema(&computed("fig1_v1"), 2));
    insta::assert_json_snapshot!("fig1_v2_extrema", extrema(&computed("fig1_v2"), 2));
    insta::assert_json_snapshot!("fig2_disk_extrema", extrema(&computed("fig2_disk"), 2));
    insta::assert_json_snapshot!("fig3_v1_extrema", extrema(&computed("fig3_v1"), 2));
    insta::assert_json_snapshot!("fig3_v2_extrema", extrema(&computed("fig3_v2"), 2));
    insta::assert_json_snapshot!("fig3_abcd_extrema", extrema(&computed("fig3_abcd"), 1));
}

/// Every row of `computed` whose abscissa is on the golden table's grid
/// equals the golden row, column by column, to [`GOLDEN_REL`] with the
/// floor [`GOLDEN_ABS`]; returns the number of values compared.
fn agrees_with_golden(computed: &Table, golden: &Table) -> usize {
    let names: Vec<&str> = computed.columns.iter().map(|c| c.name.as_str()).collect();
    let golden_names: Vec<&str> = golden.columns.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, golden_names, "{}: columns", computed.name);
    let mut n = 0;
    for row in &computed.rows {
        let Some(g) = golden
            .rows
            .iter()
            // tol: not a tolerance on a result: matches a row by its grid coordinate (printed to 12 or more digits); grid points differ by far more than 1e-9 relative.
            .find(|g| (g[0] - row[0]).abs() <= 1e-9 * row[0].abs().max(1.0))
        else {
            panic!("{}: x = {} not on the golden grid", computed.name, row[0]);
        };
        for ((c, want), name) in row.iter().zip(g).zip(&names) {
            assert!(
                (c - want).abs() <= GOLDEN_REL * want.abs() + GOLDEN_ABS,
                "{} {name} at x = {}: computed {c:e}, golden {want:e}",
                computed.name,
                row[0]
            );
            n += 1;
        }
    }
    n
}

#[derive(Serialize)]
struct Row {
    id: String,
    paper: Option<f64>,
    computed: Option<f64>,
    status: String,
    published: Option<f64>,
    exact: Option<f64>,
    note: String,
}

#[test]
#[ignore = "slow tier: every bias claim of the table recomputed (18 s)"]
fn bias_claims_table() {
    let areas = [
        "bandwidth.",
        "dispersion.",
        "scanlength.",
        "normalization.",
        "integration.",
        "line.",
        "resolution.",
    ];
    let rows: Vec<Row> = crate::claims::quick_claims()
        .iter()
        .filter(|r| areas.iter().any(|a| r.id.starts_with(a)))
        .map(|r| Row {
            id: r.id.clone(),
            paper: r.paper,
            computed: r.computed.map(sig),
            status: r.status.as_str().to_owned(),
            published: r.published.map(sig),
            exact: r.exact.map(sig),
            note: r.note.clone(),
        })
        .collect();
    assert!(
        rows.iter().all(|r| r.status != "pending"),
        "pending claims left"
    );
    insta::assert_json_snapshot!("bias_claims", rows);
}

#[derive(Serialize)]
struct IntegrationRow {
    samples_per_fringe: f64,
    monochromatic_factor: f64,
    wide_band_factor_v1_sq: f64,
    wide_band_factor_v2_sq: f64,
    max_calibrated_bias_v1: f64,
    max_calibrated_bias_v2: f64,
}

/// The integrating detector against samples per fringe (at 2.2 µm), flat
/// K band: the factors that restore each squared estimator, and the largest
/// bias left on the 43 mas disk (0–80 cycles/arcsec) once calibrated on a
/// point source seen by the same detector.
#[test]
fn integration_vs_samples_per_fringe() {
    use v2ref_core::bias::integration;
    use v2ref_core::formalism::observation::{Frequency, Observation};
    use v2ref_core::formalism::phase::SpectralPhase;
    use v2ref_core::formalism::source::Source;
    use v2ref_core::formalism::spectrum::{Band, Spectrum};
    let band = Spectrum::flat(Band::k());
    let obs = |source: Source, s: f64| {
        Observation::new(
            band.clone(),
            source,
            Frequency::SpatialFreqCpas(s),
            SpectralPhase::zero(),
        )
        .unwrap()
    };
    let rows: Vec<IntegrationRow> = [2.5, 3.0, 4.0, 6.0, 8.0, 16.0]
        .iter()
        .map(|&p| {
            let dx = 2.2 / p;
            let loss = integration::wide_band_loss(&obs(Source::Point, 0.0), dx).unwrap();
            let (mut b1, mut b2) = (0.0_f64, 0.0_f64);
            for k in 0..=80 {
                let b = integration::calibrated_bias(
                    &obs(Source::UniformDisk { diameter_mas: 43.0 }, k as f64),
                    dx,
                )
                .unwrap();
                b1 = b1.max(b.v1.abs());
                b2 = b2.max(b.v2.abs());
            }
            IntegrationRow {
                samples_per_fringe: p,
                monochromatic_factor: sig(integration::monochromatic_norm_factor(p)),
                wide_band_factor_v1_sq: sig(1.0 / loss.v1_sq),
                wide_band_factor_v2_sq: sig(1.0 / loss.v2_sq),
                max_calibrated_bias_v1: sig(b1),
                max_calibrated_bias_v2: sig(b2),
            }
        })
        .collect();
    // More samples per fringe, less of everything.
    assert!(rows
        .windows(2)
        .all(|w| w[1].wide_band_factor_v1_sq < w[0].wide_band_factor_v1_sq));
    insta::assert_json_snapshot!("integration_vs_samples_per_fringe", rows);
}
