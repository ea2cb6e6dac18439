//! The CSV spectrum reader refuses malformed files with a clear, typed
//! error naming the line, and never panics on arbitrary input.

use proptest::prelude::*;
use v2ref_core::formalism::spectrum::Spectrum;
use v2ref_core::tolerance::ROUNDING_REL;
use v2ref_core::Error;

fn reason(text: &str) -> String {
    match Spectrum::from_csv_str(text) {
        Err(Error::SpectrumTable { reason }) => reason,
        Err(e) => panic!("expected a spectrum-table error, got {e:?}"),
        Ok(_) => panic!("accepted a malformed table:\n{text}"),
    }
}

#[test]
fn a_well_formed_table_is_read_in_either_axis() {
    let by_wavelength =
        Spectrum::from_csv_str("# K band\nwavelength_um,weight\n2.0,1\n2.2,1.5\n2.4,1\n").unwrap();
    let by_wavenumber = Spectrum::from_csv_str(
        "wavenumber_per_um,weight\n0.4166666666666667,1\n0.45454545454545453,1.5\n0.5,1\n",
    )
    .unwrap();
    assert_eq!(by_wavelength.support(), by_wavenumber.support());
    let (a, b) = (
        by_wavelength.sigma_eff_per_um(),
        by_wavenumber.sigma_eff_per_um(),
    );
    assert!((a - b).abs() < ROUNDING_REL, "{a} vs {b}");
}

#[test]
fn non_numeric_cell_names_line_and_cell() {
    let r = reason("wavelength_um,weight\n2.0,1\n2.2,abc\n2.4,1\n");
    assert!(r.contains("line 3") && r.contains("abc"), "{r}");
    let r = reason("wavelength_um,weight\n2.0,1\nx2.2,1\n");
    assert!(r.contains("line 3") && r.contains("x2.2"), "{r}");
    let r = reason("wavelength_um,weight\n2.0,1\n2.2,NaN\n");
    assert!(r.contains("line 3") && r.contains("finite"), "{r}");
    let r = reason("wavelength_um,weight\n2.0,1\n2.2,inf\n");
    assert!(r.contains("line 3"), "{r}");
}

#[test]
fn unsorted_and_duplicate_wavelengths_are_refused() {
    let r = reason("wavelength_um,weight\n2.0,1\n2.4,1\n2.2,1\n");
    assert!(r.contains("line 4") && r.contains("increasing"), "{r}");
    let r = reason("wavelength_um,weight\n2.0,1\n2.2,1\n2.2,1\n");
    assert!(r.contains("line 4") && r.contains("duplicates"), "{r}");
    let r = reason("wavenumber_per_um,weight\n0.5,1\n0.45,1\n");
    assert!(r.contains("line 3"), "{r}");
}

#[test]
fn negative_weight_is_refused() {
    let r = reason("wavelength_um,weight\n2.0,1\n2.2,-0.5\n2.4,1\n");
    assert!(r.contains("line 3") && r.contains(">= 0"), "{r}");
}

#[test]
fn fewer_than_two_rows_is_refused() {
    let r = reason("wavelength_um,weight\n2.2,1\n");
    assert!(r.contains("at least 2"), "{r}");
    let r = reason("wavelength_um,weight\n");
    assert!(r.contains("at least 2"), "{r}");
    let r = reason("");
    assert!(r.contains("no header"), "{r}");
}

#[test]
fn other_defects_are_refused() {
    assert!(reason("lambda,weight\n2.0,1\n2.4,1\n").contains("header"));
    assert!(reason("wavelength_um,flux\n2.0,1\n2.4,1\n").contains("weight"));
    assert!(reason("wavelength_um,weight\n2.0,1,3\n2.4,1\n").contains("columns"));
    assert!(reason("wavelength_um,weight\n-2.0,1\n2.4,1\n").contains("> 0"));
    assert!(reason("wavelength_um,weight\n2.0,0\n2.4,0\n").contains("zero"));
    // Weights whose squares overflow, or an axis spanning 600 decades: no
    // usable weighting function.
    assert!(!reason("wavelength_um,weight\n2.0,1e300\n2.4,1e300\n").is_empty());
    assert!(!reason("wavenumber_per_um,weight\n1e-300,1\n1e300,1\n").is_empty());
}

#[test]
fn the_error_is_one_line_naming_the_library_parameter() {
    let e = Spectrum::from_csv_str("wavelength_um,weight\n2.0,1\n2.2,abc\n").unwrap_err();
    assert_eq!(e.param(), Some("spectrum"));
    assert!(e.detail().starts_with("line 3"), "{}", e.detail());
    let msg = e.to_string();
    assert!(msg.starts_with("spectrum: line 3"), "{msg}");
    assert!(!msg.contains('\n'));
}

#[test]
fn a_missing_file_keeps_the_system_error_as_source() {
    use std::error::Error as _;
    let path = std::path::Path::new("/nonexistent/spectrum.csv");
    let e = v2ref_files::formats::spectrum_csv::spectrum_from_csv_path(path).unwrap_err();
    assert_eq!(e.param(), Some("spectrum"));
    let source = e.source().expect("the io::Error is kept");
    // The system's error, shared (`Arc`) so that the error stays `Clone`.
    let io = source
        .downcast_ref::<std::sync::Arc<std::io::Error>>()
        .unwrap();
    assert_eq!(io.kind(), std::io::ErrorKind::NotFound);
    assert!(
        e.detail().starts_with("/nonexistent/spectrum.csv: "),
        "{}",
        e.detail()
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Arbitrary text: an answer, never a panic.
    #[test]
    fn garbage_never_panics(text in "\\PC{0,200}") {
        let _ = Spectrum::from_csv_str(&text);
    }

    /// Header plus arbitrary rows of number-like cells.
    #[test]
    fn numeric_garbage_never_panics(
        rows in proptest::collection::vec(
            (prop_oneof![any::<f64>().prop_map(|x| x.to_string()), "[-+0-9.eE]{0,8}", Just(String::new())],
             prop_oneof![any::<f64>().prop_map(|x| x.to_string()), "[-+0-9.eE]{0,8}"]),
            0..12),
        wavelength in any::<bool>(),
    ) {
        let mut text = String::from(if wavelength { "wavelength_um,weight\n" } else { "wavenumber_per_um,weight\n" });
        for (a, b) in rows {
            text.push_str(&format!("{a},{b}\n"));
        }
        if let Ok(sp) = Spectrum::from_csv_str(&text) {
            // Whatever is accepted is a usable weighting function.
            prop_assert!(sp.sigma_eff_per_um().is_finite() && sp.sigma_eff_per_um() > 0.0);
            prop_assert!(sp.w2_integral_um().is_finite() && sp.w2_integral_um() > 0.0);
        }
    }
}

#[test]
fn a_file_is_read_up_to_its_size_limit() {
    use v2ref_core::formalism::spectrum::MAX_SPECTRUM_CSV_BYTES;
    let table = "wavelength_um,weight\n2.0,1\n2.2,1.5\n2.4,1\n";
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("band.csv");
    // Padded with comment lines to exactly the limit: read, the same
    // spectrum as the text.
    let limit = MAX_SPECTRUM_CSV_BYTES as usize;
    assert!(
        limit >= 1 << 20,
        "a limit of {limit} bytes refuses real filter curves"
    );
    let line = format!("#{}\n", "x".repeat(99));
    let mut text = line.repeat((limit - table.len()) / line.len());
    text.push_str(&"\n".repeat(limit - table.len() - text.len()));
    text.push_str(table);
    assert_eq!(text.len(), limit);
    std::fs::write(&path, &text).unwrap();
    let read = v2ref_files::formats::spectrum_csv::spectrum_from_csv_path(&path).unwrap();
    assert_eq!(read, Spectrum::from_csv_str(table).unwrap());
    // One byte more is refused, naming the file and the limit.
    text.insert(0, '#');
    std::fs::write(&path, &text).unwrap();
    match v2ref_files::formats::spectrum_csv::spectrum_from_csv_path(&path) {
        Err(Error::SpectrumTable { reason }) => {
            assert!(
                reason.contains("band.csv") && reason.contains(&limit.to_string()),
                "{reason}"
            )
        }
        other => panic!("a file over the limit was not refused: {other:?}"),
    }
}

/// A weight per unit wavelength (`weight_per_um`) is the same spectrum as
/// its per-wavenumber form W_σ = λ² W_λ: the weighted moments agree.
#[test]
fn weight_per_um_is_converted_by_the_jacobian() {
    use v2ref_core::formalism::spectrum::Spectrum;
    let lambdas: Vec<f64> = (0..41).map(|i| 1.5 + 0.3 * i as f64 / 40.0).collect();
    let w_lambda = |l: f64| 1.0 + 2.0 * (l - 1.5);
    let per_um: String = std::iter::once("wavelength_um,weight_per_um".to_owned())
        .chain(lambdas.iter().map(|&l| format!("{l},{}", w_lambda(l))))
        .collect::<Vec<_>>()
        .join("\n");
    let per_sigma: String = std::iter::once("wavelength_um,weight".to_owned())
        .chain(
            lambdas
                .iter()
                .map(|&l| format!("{l},{}", w_lambda(l) * l * l)),
        )
        .collect::<Vec<_>>()
        .join("\n");
    let a = Spectrum::from_csv_str(&per_um).unwrap();
    let b = Spectrum::from_csv_str(&per_sigma).unwrap();
    // tol: the same σ_eff from two tables converted by λ² factors: tens of roundings of an order-one value.
    assert!((a.sigma_eff_per_um() - b.sigma_eff_per_um()).abs() < 1e-14);
    // Without the Jacobian the effective wavenumber moves measurably.
    let plain = per_um.replace("weight_per_um", "weight");
    let c = Spectrum::from_csv_str(&plain).unwrap();
    assert!((c.sigma_eff_per_um() - b.sigma_eff_per_um()).abs() > 1e-4);
}

/// Two rows are all a table needs: the quadratures integrate piece by
/// piece between the nodes, where a table is linear, so the two-row K
/// band of docs/conventions.md §2 is the built-in flat K band (the
/// wide-band V1², V2² of a 43 mas disk agree to quadrature precision).
/// This is why a two-row CSV is accepted; the test also sees a table's
/// shape (a two-row ramp is far from the flat band).
#[test]
fn a_two_row_table_is_the_flat_band_it_writes_down() {
    use v2ref_core::bias::bandwidth::curve;
    use v2ref_core::formalism::phase::SpectralPhase;
    use v2ref_core::formalism::source::Source;
    use v2ref_core::formalism::spectrum::Band;
    use v2ref_core::tolerance::QUADRATURE_REL;
    let band = Band::k();
    let (lo, hi) = (band.sigma_min_per_um(), band.sigma_max_per_um());
    let table = |w_lo: f64, w_hi: f64| {
        let text = format!("wavenumber_per_um,weight\n{lo},{w_lo}\n{hi},{w_hi}\n");
        Spectrum::from_csv_str(&text).unwrap()
    };
    let disk = Source::UniformDisk { diameter_mas: 43.0 };
    let at = [11.5, 28.364, 51.9];
    let v2 = |sp: &Spectrum| curve(sp, &disk, &SpectralPhase::zero(), &at).unwrap();
    let (two_rows, flat, ramp) = (
        v2(&table(1.0, 1.0)),
        v2(&Spectrum::flat(band)),
        v2(&table(1.0, 3.0)),
    );
    for ((t, f), r) in two_rows.iter().zip(&flat).zip(&ramp) {
        assert!((t.v1_sq - f.v1_sq).abs() < QUADRATURE_REL, "{t:?} {f:?}");
        assert!((t.v2_sq - f.v2_sq).abs() < QUADRATURE_REL, "{t:?} {f:?}");
        assert!(
            (r.v1_sq - f.v1_sq).abs() > 1e3 * QUADRATURE_REL,
            "{r:?} {f:?}"
        );
    }
}
