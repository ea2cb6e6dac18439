//! The facade's surface from a pipeline's crate (issue 53): every call
//! that takes a size, an index or a row a pipeline may read from its own
//! files returns a typed error naming the parameter and its accepted
//! range — never a panic, a wrapped overflow or an allocation that aborts
//! the process. Each call runs under `catch_unwind`, so that a panic fails
//! its case with the panic's message instead of ending the run; the
//! allocations run in a child process under an address-space limit, so
//! that an abort fails the case instead of the suite.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::OnceLock;
use v2ref::formalism::estimator::{
    all_bins, band_bins, dft, noise_bias, positive_bins, raw_estimates, BinWindow,
};
use v2ref::formalism::spectrum::{Band, Spectrum};
use v2ref::montecarlo::run_units;
use v2ref::oracle::{BiasConvention, Inputs, Model, PistonInputs, RowEstimator, Set, SourceInput};
use v2ref::Error;

/// A scan's most samples, past which no list of bins is made (2^24).
const MOST_SAMPLES: usize = 1 << 24;

/// `call()`'s error; fails the case with the panic's message where it
/// panics, and with the value where it returns one.
fn refused<T: std::fmt::Debug>(what: &str, call: impl FnOnce() -> v2ref::Result<T>) -> Error {
    match catch_unwind(AssertUnwindSafe(call)) {
        Ok(Err(e)) => e,
        Ok(Ok(v)) => panic!("{what}: accepted, gave {v:?}"),
        Err(p) => {
            let message = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            panic!("{what}: panicked: {message}")
        }
    }
}

/// Checks that `e` names `param` and says each of `accepted`.
fn names(e: &Error, param: &str, accepted: &[&str]) {
    let message = e.to_string();
    assert_eq!(e.param(), Some(param), "{message}");
    for a in accepted {
        assert!(message.contains(a), "{message:?} does not say {a:?}");
    }
}

fn inputs() -> Inputs {
    Inputs {
        samples: 16,
        source: SourceInput::Point,
        visibility: 0.6,
        photons: 50.0,
        ..Inputs::default()
    }
}

/// A model of 16 samples without piston, made once.
fn model() -> &'static Model {
    static MODEL: OnceLock<Model> = OnceLock::new();
    MODEL.get_or_init(|| Model::new(&inputs()).unwrap())
}

/// The same with the paper's piston at 100 Hz.
fn piston_model() -> &'static Model {
    static MODEL: OnceLock<Model> = OnceLock::new();
    MODEL.get_or_init(|| {
        let piston = Some(PistonInputs::paper(100.0));
        Model::new(&Inputs { piston, ..inputs() }).unwrap()
    })
}

#[test]
fn a_row_of_another_length_to_the_row_estimator_is_refused() {
    let est = RowEstimator::new(model(), BinWindow::Positive, BiasConvention::Model, true).unwrap();
    let row = model().signal.modulated.clone();
    let longer = [&row[..], &[1.0]].concat();
    names(
        &refused("estimate(17)", || est.estimate(&longer)),
        "row",
        &["17 values", "16 samples"],
    );
    names(
        &refused("estimate(15)", || est.estimate(&row[..15])),
        "row",
        &["15 values", "16 samples"],
    );
    // The row of the right length is estimated, as before.
    assert!(est.estimate(&row).unwrap().v1_sq_raw > 0.0);
}

#[test]
fn a_noise_free_row_of_another_length_or_index_is_refused() {
    for (m, what) in [(model(), "no piston"), (piston_model(), "piston")] {
        let rows = m.rows(3, 7, 1).unwrap();
        let mut short = vec![0.0; 15];
        let e = refused(what, || rows.noise_free_row(0, &mut short));
        names(&e, "out", &["15", "16 values"]);
        let mut out = vec![f64::NAN; 16];
        for s in [3, 1_000_000_000, u64::MAX] {
            names(
                &refused(what, || rows.noise_free_row(s, &mut out)),
                "row",
                &["0 to 2"],
            );
        }
        assert!(out.iter().all(|v| v.is_nan()), "{what}: nothing written");
        rows.noise_free_row(2, &mut out).unwrap();
        assert!(out.iter().all(|v| v.is_finite()), "{what}");
    }
}

#[test]
fn units_and_rows_beyond_the_set_are_refused() {
    // 3 rows: one unit. Before: unit 1 had 8192 rows (a wrapped subtraction).
    let rows = model().rows(3, 7, 1).unwrap();
    assert_eq!((rows.units(), rows.unit_rows(0).unwrap()), (1, 3));
    for u in [1, u64::MAX] {
        names(
            &refused("unit_rows", || rows.unit_rows(u)),
            "unit",
            &["0 to 0"],
        );
    }
    let filled = run_units(7, 1, 1, |_, rng| {
        let mut out = Vec::new();
        let e = refused("fill_unit", || rows.fill_unit(1, rng, &mut out));
        (e, out.len())
    })
    .unwrap();
    names(&filled[0].0, "unit", &["0 to 0"]);
    assert_eq!(filled[0].1, 0, "nothing appended");
    let e = refused("map_units", || rows.map_units(0..5, 1, |_, b| Ok(b.len())));
    names(&e, "unit", &["0 to 0"]);
    assert_eq!(rows.map_units(0..1, 1, |_, b| Ok(b.len())).unwrap(), [48]);
    // With piston, row 3 of 3 read the last sequence; now refused.
    let piston = piston_model().rows(3, 7, 1).unwrap();
    for s in [3, u64::MAX] {
        names(
            &refused("sequence_of", || piston.sequence_of(s)),
            "row",
            &["0 to 2"],
        );
    }
    assert!(piston.sequence_of(2).unwrap() < piston.sequences());
}

#[test]
fn bin_lists_past_a_scans_most_samples_are_refused() {
    let k = Spectrum::flat(Band::k());
    let n = MOST_SAMPLES + 1;
    let accepted = ["1.6777217e7", "0 to 16777216"];
    names(
        &refused("positive_bins", || positive_bins(n)),
        "samples",
        &accepted,
    );
    names(&refused("all_bins", || all_bins(n)), "samples", &accepted);
    names(
        &refused("band_bins", || band_bins(n, 0.5, 0.4, 0.5)),
        "samples",
        &accepted,
    );
    for w in [BinWindow::Positive, BinWindow::Band, BinWindow::All] {
        names(
            &refused("bins", || w.bins(n, 0.5, &k)),
            "samples",
            &accepted,
        );
    }
    names(
        &refused("all_bins", || all_bins(usize::MAX)),
        "samples",
        &["0 to 16777216"],
    );
    assert_eq!(
        positive_bins(MOST_SAMPLES).unwrap().len(),
        MOST_SAMPLES / 2 - 1
    );
}

#[test]
fn a_bin_past_the_spectrum_is_refused() {
    let spectrum = dft(&[1.0, 2.0, 0.5, -1.0, 3.0, 0.0, 1.0, -2.0]);
    for k in [8, 1 << 62, usize::MAX] {
        names(
            &refused("raw_estimates", || raw_estimates(&spectrum, &[1, k])),
            "bins",
            &["0 to 7"],
        );
    }
    names(
        &refused("raw_estimates", || raw_estimates(&[], &[0])),
        "bins",
        &["no bin"],
    );
    assert!(raw_estimates(&spectrum, &[1, 7]).unwrap().v1_sq > 0.0);
}

#[test]
fn a_noise_bias_of_bins_past_the_samples_or_of_bad_variances_is_refused() {
    let variance = [1.0; 8];
    // Before: bin 2^62 (i k wrapped) and bin 9 (read as bin 1) gave a bias.
    for k in [8, 9, 1 << 62] {
        names(
            &refused("noise_bias", || noise_bias(&variance, &[k])),
            "bins",
            &["0 to 7"],
        );
    }
    // Before: a negative variance gave a negative bias, 1e308 an infinite one.
    let e = refused("noise_bias", || noise_bias(&[-1.0; 8], &[1]));
    names(&e, "variance", &["finite and >= 0"]);
    names(
        &refused("noise_bias", || noise_bias(&[f64::NAN; 8], &[1])),
        "variance",
        &[">= 0"],
    );
    names(
        &refused("noise_bias", || noise_bias(&[1e308; 8], &[1, 2])),
        "variance",
        &["overflows"],
    );
    let bias = noise_bias(&variance, &[1, 2]).unwrap();
    assert_eq!(bias.v1_sq, 16.0);
}

/// The name of the variable that runs a case in the child.
const CHILD: &str = "V2REF_SURFACE_CHILD";

/// The address-space limit of the child, KiB (2 GB): the test binary runs
/// in it, 4 GiB does not fit.
const CHILD_LIMIT_KIB: u64 = 2_000_000;

/// Runs `case` (a test of this file) in a child of this test binary under
/// an address-space limit; fails with the child's output unless it passes.
fn in_limited_child(case: &str) {
    let exe = std::env::current_exe().unwrap();
    let script = format!("ulimit -v {CHILD_LIMIT_KIB} && exec \"$0\" \"$@\"");
    let out = std::process::Command::new("sh")
        .args(["-c", &script])
        .arg(exe)
        .args(["--exact", &format!("robustness_surface::{case}")])
        .args(["--include-ignored", "--test-threads", "1"])
        .env(CHILD, "1")
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&out.stdout) + String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{case} under ulimit -v {CHILD_LIMIT_KIB}: {:?}\n{said}",
        out.status
    );
    assert!(said.contains("1 passed"), "{said}");
}

/// Checks `e` is the refusal of memory the process cannot have.
fn refused_memory(e: &Error, param: &str) {
    names(e, param, &["GiB", "cannot allocate"]);
}

#[test]
#[ignore = "run by sets_whose_values_cannot_be_allocated_are_refused, in a child"]
fn child_set_of_4_gib() {
    if std::env::var_os(CHILD).is_none() {
        return;
    }
    // 2^22 rows of 128 samples: 2^29 values, 4 GiB. Before: the process
    // aborted ("memory allocation of 2147483648 bytes failed") after 1.5
    // CPU minutes of rows.
    let big = Inputs {
        samples: 128,
        ..inputs()
    };
    refused_memory(
        &refused("Set::synthesize", || Set::synthesize(&big, 1 << 22, 1)),
        "rows",
    );
}

#[test]
#[ignore = "run by sets_whose_values_cannot_be_allocated_are_refused, in a child"]
fn child_estimates_of_1_gib_of_rows() {
    if std::env::var_os(CHILD).is_none() {
        return;
    }
    // 2^25 rows of 4 samples (1 GiB): their estimates take 1.5 GiB more.
    let model = Model::new(&Inputs {
        samples: 4,
        ..inputs()
    })
    .unwrap();
    let est = RowEstimator::new(&model, BinWindow::All, BiasConvention::Model, true).unwrap();
    let rows = vec![1.0; 4 << 25];
    refused_memory(
        &refused("estimate_rows", || est.estimate_rows(&rows, 1)),
        "interferograms",
    );
}

#[test]
fn sets_whose_values_cannot_be_allocated_are_refused() {
    in_limited_child("child_set_of_4_gib");
    in_limited_child("child_estimates_of_1_gib_of_rows");
}
