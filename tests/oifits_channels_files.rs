//! The files of issue 54's OIFITS channels beyond the crate's own
//! reader: the six-channel file the Python suite reads with astropy
//! (`tests/python/test_oifits_channels.py`) is what the writer writes today,
//! and fitsverify finds nothing in a file of six channels.

use crate::oifits_channels::{channels, inputs, timeless, written, WINDOW};
use std::path::Path;
use v2ref_core::conformance::score::Estimator;
use v2ref_oifits::docs::estimates_doc_channels;
use v2ref_oifits::{to_bytes, write_oifits, ObservingContext};

/// The file `tests/python/test_oifits_channels.py` reads with astropy: six
/// channels of K, 8 rows, V1² of row r (0-based), channel j (0-based) =
/// `0.1 (r + 1) + 0.01 (j + 1)` and V2² that plus 0.5 (exact sums both
/// sides compute alike), (row 2, channel 4) flagged in V2².
const FIXTURE: &str = "tests/data/oifits_channels6.fits";

fn fixture_doc() -> v2ref_oifits::OifitsDoc {
    let six = channels(6);
    let v = |e: f64, r: usize, j: usize| 0.5 * e + 0.1 * (r + 1) as f64 + 0.01 * (j + 1) as f64;
    let cols: Vec<(Estimator, Vec<f64>)> = [(Estimator::V1Sq, 0.0), (Estimator::V2Sq, 1.0)]
        .iter()
        .map(|&(est, e)| (est, (0..8 * 6).map(|i| v(e, i / 6, i % 6)).collect()))
        .collect();
    let mut doc = estimates_doc_channels(
        (&inputs(), &six),
        &cols,
        WINDOW,
        &ObservingContext::default(),
    )
    .unwrap();
    doc.tables[1].flag[2 * 6 + 4] = true;
    doc
}

#[test]
fn the_python_suites_file_is_what_the_writer_writes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(FIXTURE);
    let doc = fixture_doc();
    if std::env::var_os("V2REF_WRITE_OIFITS_FIXTURE").is_some() {
        write_oifits(&path, "out", &doc).unwrap();
    }
    let stored = std::fs::read(&path).unwrap();
    assert!(
        timeless(&stored) == timeless(&to_bytes(&doc).unwrap()),
        "{FIXTURE} is not what the writer writes: if the change is meant, \
         rewrite it with V2REF_WRITE_OIFITS_FIXTURE=1 and say why in the commit"
    );
}

#[test]
fn fitsverify_finds_nothing_in_a_file_of_six_channels() {
    let dir = tempfile::tempdir().unwrap();
    let path = written(dir.path(), &channels(6));
    let Ok(out) = std::process::Command::new("fitsverify").arg(&path).output() else {
        // .ci/run installs it and then requires it.
        assert!(
            std::env::var_os("V2REF_REQUIRE_FITSVERIFY").is_none(),
            "V2REF_REQUIRE_FITSVERIFY is set and fitsverify does not run"
        );
        eprintln!("fitsverify not installed: {} not verified", path.display());
        return;
    };
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        report.contains("Verification found 0 warning(s) and 0 error(s)"),
        "{report}"
    );
}
