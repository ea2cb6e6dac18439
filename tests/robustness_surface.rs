//! The facade's surface from a pipeline's crate (issue 53): every call
//! that takes a size, an index or a row a pipeline may read from its own
//! files returns a typed error naming the parameter and its accepted
//! range — never a panic, an overflow or an allocation that aborts the
//! process. Each call runs under `catch_unwind`, so that a panic fails its
//! case with the panic's message instead of ending the run.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::OnceLock;
use v2ref::formalism::estimator::{
    all_bins, band_bins, dft, noise_bias, positive_bins, raw_estimates, BinWindow,
};
use v2ref::formalism::spectrum::{Band, Spectrum};
use v2ref::oracle::{BiasConvention, Inputs, Model, PistonInputs, RowEstimator, Set, SourceInput};
use v2ref::Error;

/// `call()`'s error, failing the case with the panic's message where it
/// panics and with the value where it returns one.
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

/// Checks that `e` names `param` and states what is accepted (each of
/// `accepted`).
fn names(e: &Error, param: &str, accepted: &[&str]) {
    let message = e.to_string();
    assert_eq!(e.param(), Some(param), "{message}");
    for a in accepted {
        assert!(message.contains(a), "{message:?} does not say {a:?}");
    }
}

/// A small model (16 samples), made once.
fn model() -> &'static Model {
    static MODEL: OnceLock<Model> = OnceLock::new();
    MODEL.get_or_init(|| {
        let inputs = Inputs {
            samples: 16,
            source: SourceInput::Point,
            visibility: 0.6,
            photons: 50.0,
            ..Inputs::default()
        };
        Model::new(&inputs).unwrap()
    })
}

/// The same model with the paper's piston at 100 Hz.
fn piston_model() -> &'static Model {
    static MODEL: OnceLock<Model> = OnceLock::new();
    MODEL.get_or_init(|| {
        let inputs = Inputs {
            piston: Some(PistonInputs::paper(100.0)),
            ..model().inputs.clone()
        };
        Model::new(&inputs).unwrap()
    })
}

#[test]
fn a_row_of_another_length_to_the_row_estimator_is_refused() {
    let est = RowEstimator::new(model(), BinWindow::Positive, BiasConvention::Model, true)
        .unwrap();
    let row = model().signal.modulated.clone();
    assert!(est.estimate(&row).is_ok());
    let longer = [&row[..], &[1.0]].concat();
    names(&refused("estimate(17 values)", || est.estimate(&longer)), "row", &["17", "16 samples"]);
    names(&refused("estimate(15 values)", || est.estimate(&row[..15])), "row", &["15", "16 samples"]);
}
