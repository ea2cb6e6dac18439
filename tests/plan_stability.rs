//! The planner's promise as a property of a setting, and its detector:
//!
//! - **a setting's promise is its own**: the same setting in two grids
//!   that differ in every other frequency gives the same bits (its piston
//!   Monte Carlos are keyed by the setting and sized by the atmosphere, not
//!   by the grid or by the n of another setting);
//! - **the intervals hold the noise Monte Carlo's scatter**: under the
//!   `counts` convention the time's interval is not zero wide even when the
//!   piston is negligible;
//! - **the grid's edges and the text's words** (issue 55): a stroke
//!   rounded to whole samples is still the bottom of its grid; an
//!   inflation below 1 is explained where it is printed;
//! - **the detector's edge**: `--frame-rate-hz` bounds the grid at frame
//!   rate / samples per fringe, and a recommendation there is said to be
//!   the detector's edge; a bad rate exits 2 naming the flag, and a
//!   library grid faster than the detector is refused naming `fringe_hz`.

use crate::run::v2ref;
use v2ref_commands::plan::{plan, PlanInputs, Target};
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::simulator::{Inputs, PistonInputs, SourceInput, SpectrumInput};

/// An H-band 2 mas disk on 100 m at 1e6 photons/s through 1 m apertures
/// with a 25 m outer scale: noise and piston both matter.
fn inputs(fringe_hz: Vec<f64>, bias: BiasConvention) -> PlanInputs {
    PlanInputs {
        instrument: Inputs {
            spectrum: SpectrumInput::Flat {
                wavelength_um: 1.65,
                bandwidth_nm: 300.0,
            },
            source: SourceInput::Ud { diameter_mas: 2.0 },
            baseline_m: 100.0,
            ..Inputs::default()
        },
        atmosphere: PistonInputs {
            wavelength_um: 1.65,
            seeing_arcsec: 0.8,
            outer_scale_m: Some(25.0),
            aperture_m: 1.0,
            ..PistonInputs::paper(1.0)
        },
        samples_per_fringe: 4.0,
        photon_rate_per_s: 1e6,
        dead_time_s: 0.0,
        frame_rate_hz: None,
        fringe_hz,
        stroke_um: vec![16.0],
        target: Target::SigmaV2(2e-3),
        scans: 2000,
        seed: 5,
        diameter_err_mas: 0.0,
        bias,
    }
}

/// The point at 1000 Hz is the same, bit for bit, in a grid with 300 Hz
/// and in one with 600 Hz beside it: per-scan terms, the observation's
/// promise and its interval.
#[test]
fn a_settings_promise_does_not_depend_on_the_rest_of_the_grid() {
    let a = plan(
        &inputs(vec![300.0, 1000.0], BiasConvention::Counts),
        0,
        &|_| {},
    )
    .unwrap();
    let b = plan(
        &inputs(vec![600.0, 1000.0], BiasConvention::Counts),
        1,
        &|_| {},
    )
    .unwrap();
    let at = |p: &v2ref_commands::plan::Plan| {
        p.points
            .iter()
            .filter(|q| q.fringe_hz == 1000.0)
            .copied()
            .collect::<Vec<_>>()
    };
    let (pa, pb) = (at(&a), at(&b));
    assert_eq!(pa.len(), 2);
    assert!(pa.iter().any(|p| p.observation.is_some()), "{pa:?}");
    for (x, y) in pa.iter().zip(&pb) {
        assert_eq!(x, y, "the same setting, two grids");
        if let Some(o) = x.observation {
            assert_eq!(o.sigma.to_bits(), y.observation.unwrap().sigma.to_bits());
        }
    }
}

/// Under `counts` the noise per scan comes from a Monte Carlo: its
/// interval enters the time's, so no solved point has a zero-wide one.
#[test]
fn the_noise_monte_carlo_widens_the_time_interval() {
    let p = plan(&inputs(vec![1000.0], BiasConvention::Counts), 0, &|_| {}).unwrap();
    let solved: Vec<_> = p
        .points
        .iter()
        .filter(|q| q.observation.is_some())
        .collect();
    assert!(!solved.is_empty());
    for q in solved {
        let o = q.observation.unwrap();
        assert!(
            o.sigma_noise_per_scan_lower < o.sigma_noise_per_scan,
            "{o:?}"
        );
        assert!(q.time_lower_s.unwrap() < q.time_s.unwrap(), "{q:?}");
    }
}

fn plan_json(extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "plan",
        "--wavelength-um",
        "1.65",
        "--bandwidth-nm",
        "300",
        "--diameter-mas",
        "1",
        "--baseline-m",
        "100",
        "--outer-scale-m",
        "25",
        "--photon-rate-per-s",
        "1e8",
        "--stroke-um",
        "16",
        "--scans",
        "500",
        "--quiet",
        "--json",
    ];
    args.extend_from_slice(extra);
    let (code, out, err) = v2ref(&args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

/// A bright star wants the fastest fringe: with a 6 kHz detector at 4
/// samples per fringe the grid stops at 1500 Hz, which the plan
/// recommends and calls the detector's edge; a given grid is cut there
/// and gains the edge.
#[test]
fn the_frame_rate_bounds_the_grid_and_names_the_detectors_edge() {
    let j = plan_json(&["--frame-rate-hz", "6000", "--fringe-hz", "200:1500:4:log"]);
    let grid: Vec<f64> = serde_json::from_value(j["inputs"]["fringe_hz"].clone()).unwrap();
    assert_eq!(grid.last(), Some(&1500.0), "{grid:?}");
    assert_eq!(j["recommended"]["fringe_hz"].as_f64(), Some(1500.0));
    assert_eq!(j["at_detector_edge"].as_bool(), Some(true));
    let note = j["grid_edge"].as_str().unwrap();
    assert!(note.contains("detector's edge"), "{note}");
    // A grid beyond the detector: cut, and its top is the edge.
    let j = plan_json(&[
        "--frame-rate-hz",
        "6000",
        "--fringe-hz",
        "500",
        "--fringe-hz",
        "3000",
    ]);
    let grid: Vec<f64> = serde_json::from_value(j["inputs"]["fringe_hz"].clone()).unwrap();
    assert_eq!(grid, vec![500.0, 1500.0]);
    // Without a detector, the top of the grid is the grid's corner.
    let j = plan_json(&["--fringe-hz", "200:1500:4:log"]);
    assert_eq!(j["at_detector_edge"].as_bool(), Some(false));
    let note = j["grid_edge"].as_str().unwrap();
    assert!(
        note.contains("top of the grid") && note.contains("--frame-rate-hz"),
        "{note}"
    );
}

/// The stroke's grid edge is judged in whole samples (issue 55: none of
/// 211 season rows said so): 16 µm at λ0/4 = 0.4125 µm is 39 samples, a
/// true stroke of 16.0875 µm, above the grid's 16; the note still says
/// the recommendation sits at the bottom of the stroke grid, naming both.
#[test]
fn a_stroke_rounded_up_to_whole_samples_is_still_the_bottom_of_its_grid() {
    let j = plan_json(&["--fringe-hz", "1500", "--stroke-um", "32"]);
    let strokes: Vec<f64> = serde_json::from_value(j["inputs"]["stroke_um"].clone()).unwrap();
    assert_eq!(strokes, vec![16.0, 32.0]);
    let r = &j["recommended"];
    assert_eq!(r["samples"].as_u64(), Some(39), "{r}");
    assert!(r["stroke_um"].as_f64().unwrap() > 16.0, "{r}");
    let note = j["grid_edge"].as_str().expect("a grid-edge note");
    assert!(
        note.contains("stroke 16.08")
            && note.contains("(39 whole samples")
            && note.contains("bottom of the grid (16 to 32 um)"),
        "{note}"
    );
}

/// An inflation below 1 is explained where it is printed (issue 55:
/// "inflation 0.07" stood unexplained): a faint H-band star at 1000 Hz,
/// whose observation of about 15 000 scans spans many piston correlation
/// times, prints an inflation below 1 with what it is and why.
#[test]
fn an_inflation_below_one_is_explained_in_the_text() {
    let (code, out, err) = v2ref(&[
        "plan",
        "--wavelength-um",
        "1.65",
        "--bandwidth-nm",
        "300",
        "--diameter-mas",
        "1",
        "--baseline-m",
        "100",
        "--outer-scale-m",
        "25",
        "--photon-rate-per-s",
        "2e4",
        "--read-noise",
        "1",
        "--fringe-hz",
        "1000",
        "--stroke-um",
        "16",
        "--target-sigma-v2",
        "3e-3",
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");
    let shown = out
        .split("inflation ")
        .nth(1)
        .expect("an inflation printed");
    let inflation: f64 = shown.split(' ').next().unwrap().parse().unwrap();
    // tol: not a tolerance: the regime, an inflation below 1.
    assert!(inflation < 1.0, "{out}");
    for words in [
        "inflation: the piston variance of the mean of n consecutive scans over that of n independent scans",
        "below 1 here",
        "net drift",
    ] {
        assert!(out.contains(words), "{words:?} not in {out}");
    }
}

/// Bad rates exit 2 with one line naming the flag and its range; the
/// library refuses a grid faster than its detector, naming `fringe_hz`.
#[test]
fn a_bad_frame_rate_is_refused_by_name() {
    for bad in ["0", "-5", "1e10", "nan"] {
        let (code, out, err) = v2ref(&["plan", "--frame-rate-hz", bad, "--quiet"]);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(out.is_empty());
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains("--frame-rate-hz"), "{err}");
    }
    let i = PlanInputs {
        frame_rate_hz: Some(4000.0),
        ..inputs(vec![500.0, 2000.0], BiasConvention::Model)
    };
    let e = plan(&i, 0, &|_| {}).unwrap_err().to_string();
    assert!(
        e.contains("fringe_hz") && e.contains("frame_rate_hz"),
        "{e}"
    );
}
