//! Checking a third-party V² implementation against v2ref's golden data.
//!
//! Run: `cargo run --release --example check_against_golden`
//!
//! The "third-party" code below is written the way another project might:
//! it does not use the v2ref library at all. It computes the wide-band V1
//! and V2 of a uniform disk in a flat band with its own Bessel function
//! (the trapezoid rule on Bessel's integral, exponentially convergent for a
//! periodic integrand) and a midpoint rule over wavenumber, then compares
//! with `golden/fig1_v1.csv` and `golden/fig1_v2.csv` (the curves of the
//! paper's Fig. 1). Any language can do the same: the golden files are CSV
//! with a `name [unit]` header.

use std::f64::consts::PI;
use std::path::Path;

/// J1(x) = (1/2π) ∫_0^{2π} cos(x sin τ − τ) dτ by the trapezoid rule.
fn their_j1(x: f64) -> f64 {
    let n = 96;
    (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            (x * t.sin() - t).cos()
        })
        .sum::<f64>()
        / n as f64
}

/// Their uniform-disk visibility at spatial frequency `s` (cycles/arcsec).
fn their_disk(diameter_mas: f64, s: f64) -> f64 {
    let z = PI * diameter_mas * 1e-3 * s;
    if z.abs() < 1e-8 {
        1.0
    } else {
        2.0 * their_j1(z) / z
    }
}

/// Their wide-band (V1, V2) for a flat band [λ0 − Δλ/2, λ0 + Δλ/2] at
/// spatial frequency `s` at the band's mean wavenumber.
fn their_estimators(diameter_mas: f64, lambda_um: f64, width_um: f64, s: f64) -> (f64, f64) {
    let (lo, hi) = (
        1.0 / (lambda_um + width_um / 2.0),
        1.0 / (lambda_um - width_um / 2.0),
    );
    let sigma_eff = 0.5 * (lo + hi);
    let n = 1500;
    let (mut sum_v, mut sum_v2) = (0.0, 0.0);
    for k in 0..n {
        let sigma = lo + (hi - lo) * (k as f64 + 0.5) / n as f64;
        let v = their_disk(diameter_mas, s * sigma / sigma_eff);
        sum_v += v;
        sum_v2 += v * v;
    }
    ((sum_v2 / n as f64).sqrt(), (sum_v / n as f64).abs())
}

/// Reads a golden CSV: header cells and rows.
fn read_csv(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header = lines.next().ok_or("empty file")?;
    let names = header
        .split(',')
        .map(|h| h.split(" [").next().unwrap_or(h).to_owned())
        .collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|c| c.parse::<f64>().map_err(|e| e.to_string()))
                .collect()
        })
        .collect::<Result<_, _>>()?;
    Ok((names, rows))
}

/// Compares their implementation with one golden table; returns the largest
/// absolute difference of (estimator − V mono) over every column and row.
fn compare(golden_dir: &Path, estimator: usize) -> Result<f64, String> {
    let file = golden_dir.join(format!("fig1_v{estimator}.csv"));
    let (names, rows) = read_csv(&file)?;
    let prefix = format!("v{estimator}_minus_vmono_");
    let mut worst: f64 = 0.0;
    for (j, name) in names.iter().enumerate() {
        let Some(tag) = name.strip_prefix(&prefix) else {
            continue;
        };
        let width_nm: f64 = tag
            .trim_end_matches("nm")
            .replace('p', ".")
            .parse()
            .map_err(|e| format!("{name}: {e}"))?;
        for row in rows.iter().step_by(13) {
            let s = row[0];
            let (v1, v2) = their_estimators(43.0, 2.2, width_nm * 1e-3, s);
            let theirs = if estimator == 1 { v1 } else { v2 } - their_disk(43.0, s).abs();
            worst = worst.max((theirs - row[j]).abs());
        }
    }
    Ok(worst)
}

/// Checks both panels; `Ok(worst difference)` when within `tolerance`.
pub fn check(golden_dir: &Path, tolerance: f64) -> Result<f64, String> {
    let mut worst: f64 = 0.0;
    for estimator in [1, 2] {
        let w = compare(golden_dir, estimator)?;
        println!("fig1_v{estimator}: largest |their (V - V mono) - golden| = {w:.2e}");
        worst = worst.max(w);
    }
    if worst <= tolerance {
        Ok(worst)
    } else {
        Err(format!(
            "their implementation differs from the golden data by {worst:.2e} > {tolerance:.0e}"
        ))
    }
}

#[allow(dead_code)] // also compiled into tests/examples.rs, which calls `check`
fn main() {
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("golden");
    match check(&golden, v2ref_core::tolerance::EXAMPLE_GOLDEN_ABS) {
        Ok(_) => println!("PASS: the implementation agrees with v2ref's Fig. 1 to 1e-6"),
        Err(e) => {
            eprintln!("FAIL: {e}");
            std::process::exit(1);
        }
    }
}
