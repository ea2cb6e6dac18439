//! Issue 54, OIFITS in spectral channels (NWAVE = C): the broadband file
//! unchanged when there is one channel; C channels written with each
//! channel's wavelength, width and closed-form error, read back bit for
//! bit by the crate's reader and an independent one; a pipeline's file
//! (written with the tests' own plain writer, `tests/fits_plain.rs`, in
//! increasing or decreasing wavelength, EFF_WAVE as float32, FLAG per
//! channel) read per channel; and the refusals, one line each.

use crate::fits_plain::{self, Card, Column};
use std::path::{Path, PathBuf};
use v2ref_core::conformance::estimate::BiasConvention;
use v2ref_core::conformance::score::Estimator;
use v2ref_core::conformance::sidecar::{ConventionTruth, EstimatorTruth, TruthSource};
use v2ref_core::formalism::channels::Channels;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::noise::calibrated::expectation;
use v2ref_core::noise::Formula;
use v2ref_core::simulator::channels::channel_models;
use v2ref_core::simulator::{Inputs, Model};
use v2ref_oifits::docs::{estimates_doc, estimates_doc_channels};
use v2ref_oifits::{
    min_unflagged_rows, read_oifits_estimates, read_vis2_tables, to_bytes, wavelength_ranges_m,
    write_oifits, Choice, Expected, ObservingContext, OifitsEstimates,
};

const ROWS: usize = 40;
pub(crate) const WINDOW: (BinWindow, BiasConvention) = (BinWindow::Positive, BiasConvention::Model);

/// K band, flat, 512 samples 0.5 µm apart: bins 1/256 µm⁻¹ apart, about
/// 3.5 of them in each of six equal channels.
pub(crate) fn inputs() -> Inputs {
    Inputs {
        samples: 512,
        ..Inputs::default()
    }
}

pub(crate) fn channels(count: usize) -> Channels {
    Channels::equal(&inputs().spectrum.spectrum().unwrap(), count).unwrap()
}

/// A value for row `r`, channel `j` of estimator `e` (0: V1², 1: V2²):
/// distinct for every (e, r, j), and not round in binary.
fn value(e: usize, r: usize, j: usize) -> f64 {
    0.5 + 0.3 * ((r as f64 * 0.618_034 + j as f64 * 1.1 + e as f64 * 0.37).sin())
}

/// Both estimators' rows × C values, row after row.
fn columns(c: usize) -> Vec<(Estimator, Vec<f64>)> {
    [Estimator::V1Sq, Estimator::V2Sq]
        .iter()
        .enumerate()
        .map(|(e, &est)| {
            let v = (0..ROWS)
                .flat_map(|r| (0..c).map(move |j| value(e, r, j)))
                .collect();
            (est, v)
        })
        .collect()
}

/// The file's bytes with what changes with the time of writing blanked:
/// the cards `DATE`, `CHECKSUM` and `DATASUM` (its comment says when).
pub(crate) fn timeless(bytes: &[u8]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for card in out.chunks_mut(80) {
        if [&b"DATE    ="[..], b"CHECKSUM=", b"DATASUM ="]
            .iter()
            .any(|k| card.starts_with(k))
        {
            card.fill(b' ');
        }
    }
    out
}

fn expected(c: Option<&Channels>) -> Expected {
    Expected {
        rows: ROWS as u64,
        band_m: (2.0e-6, 2.4e-6),
        channels_m: c.map(wavelength_ranges_m),
        bins: WINDOW.0,
        bias: WINDOW.1,
    }
}

fn read(path: &Path, estimator: Option<Estimator>, c: Option<&Channels>) -> OifitsEstimates {
    let choice = Choice {
        estimator,
        ..Choice::default()
    };
    read_oifits_estimates(path, &choice, &expected(c)).unwrap()
}

/// The message of a refusal: one line, naming the parameter and the file.
fn refusal(path: &Path, estimator: Option<Estimator>, c: Option<&Channels>) -> String {
    let choice = Choice {
        estimator,
        ..Choice::default()
    };
    let e = read_oifits_estimates(path, &choice, &expected(c)).unwrap_err();
    assert_eq!(e.param(), Some("estimates"), "{e}");
    let message = e.to_string();
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(message.contains(&path.display().to_string()), "{message}");
    message
}

pub(crate) fn written(dir: &Path, c: &Channels) -> PathBuf {
    let path = dir.join("six.fits");
    let doc = estimates_doc_channels(
        (&inputs(), c),
        &columns(c.count()),
        WINDOW,
        &ObservingContext::default(),
    )
    .unwrap();
    write_oifits(&path, "out", &doc).unwrap();
    path
}

/// One pipeline table of the tests' plain writer: its INSNAME, its
/// rows × C values (row after row) and flags.
type PlainTable<'a> = (&'a str, Vec<f64>, Vec<bool>);

/// An OIFITS v2 file as another pipeline writes it: per table an
/// `OI_WAVELENGTH` (`EFF_WAVE` as float32 in the order given, or as
/// doubles) and an `OI_VIS2` of NWAVE = `eff_wave.len()` values per row,
/// no v2ref keyword.
fn plain(path: &Path, eff_wave: Result<Vec<f32>, Vec<f64>>, tables: &[PlainTable]) {
    let c = match &eff_wave {
        Ok(w) => w.len(),
        Err(w) => w.len(),
    };
    let mut hdus = Vec::new();
    for (ins, vals, flags) in tables {
        let keys = || vec![("OI_REVN", Card::Int(2)), ("INSNAME", Card::Str(ins))];
        let wave = match &eff_wave {
            Ok(w) => Column::F32("EFF_WAVE", w.clone()),
            Err(w) => Column::F64("EFF_WAVE", w.clone()),
        };
        hdus.push(("OI_WAVELENGTH", keys(), vec![wave]));
        let rows = vals.len() / c;
        hdus.push((
            "OI_VIS2",
            keys(),
            vec![
                Column::I16("TARGET_ID", vec![1; rows]),
                Column::F64("MJD", (0..rows).map(|r| 60_000.0 + r as f64).collect()),
                Column::F64s("VIS2DATA", c, vals.clone()),
                Column::F64s("VIS2ERR", c, vec![0.1; vals.len()]),
                Column::Logicals("FLAG", c, flags.clone()),
            ],
        ));
    }
    fits_plain::write(path, &hdus);
}

/// Estimator `e`'s values laid out in the file's column order: column k
/// holds the set's channel `order[k]`.
fn laid_out(e: usize, order: &[usize]) -> Vec<f64> {
    (0..ROWS)
        .flat_map(|r| order.iter().map(move |&j| value(e, r, j)))
        .collect()
}

/// `EFF_WAVE` of each set channel, m: `1/σ_eff` of its own spectrum.
fn eff_waves_m(c: &Channels) -> Vec<f64> {
    c.spectra()
        .iter()
        .map(|s| 1e-6 / s.sigma_eff_per_um())
        .collect()
}

#[test]
fn one_channel_writes_the_broadband_file_byte_for_byte() {
    let inputs = inputs();
    let model = Model::new(&inputs).unwrap();
    let observing = ObservingContext::default();
    let broadband = estimates_doc(&model, &columns(1), WINDOW, &observing).unwrap();
    let today = timeless(&to_bytes(&broadband).unwrap());
    let spectrum = inputs.spectrum.spectrum().unwrap();
    for one in [Channels::whole(&spectrum), channels(1)] {
        let doc = estimates_doc_channels((&inputs, &one), &columns(1), WINDOW, &observing).unwrap();
        assert_eq!(timeless(&to_bytes(&doc).unwrap()), today);
    }
    // The broadband header says so; six channels say they are dispersed.
    let hdus = |bytes: &[u8]| String::from_utf8_lossy(bytes).into_owned();
    assert!(hdus(&today).contains("INSMODE = 'BROADBAND'"));
    let six = channels(6);
    let doc = estimates_doc_channels((&inputs, &six), &columns(6), WINDOW, &observing).unwrap();
    let text = hdus(&to_bytes(&doc).unwrap());
    assert!(text.contains("INSMODE = 'DISPERSED'"), "INSMODE");
    assert!(text.contains("TDIM5   = '(6)     '"), "TDIM5");
}

#[test]
fn six_channels_are_written_with_each_channels_wavelength_width_and_error() {
    let dir = tempfile::tempdir().unwrap();
    let six = channels(6);
    let path = written(dir.path(), &six);
    // The independent reader: OI_WAVELENGTH one row per channel, in the
    // set's order (increasing wavenumber, so EFF_WAVE decreases).
    let hdus = fits_plain::read(&path);
    let wave = fits_plain::hdu(&hdus, "OI_WAVELENGTH");
    let want: Vec<f32> = eff_waves_m(&six).iter().map(|&w| w as f32).collect();
    assert_eq!(wave.f32_col("EFF_WAVE"), want);
    assert!(want.windows(2).all(|w| w[0] > w[1]), "{want:?}");
    let widths: Vec<f32> = six
        .edges_per_um()
        .iter()
        .map(|&(lo, hi)| (1e-6 / lo - 1e-6 / hi) as f32)
        .collect();
    assert_eq!(wave.f32_col("EFF_BAND"), widths);
    let vis2 = fits_plain::hdu(&hdus, "OI_VIS2");
    assert_eq!(vis2.key("TFORM5"), "6D");
    assert_eq!(vis2.key("TDIM10"), "(6)");
    let v1 = &columns(6)[0].1;
    let got = vis2.f64_values("VIS2DATA");
    assert_eq!(got.len(), ROWS * 6);
    assert!(got.iter().zip(v1).all(|(a, b)| a.to_bits() == b.to_bits()));
    assert!(vis2.logical_values("FLAG").iter().all(|f| !f));
    // VIS2ERR of channel j: the closed form of channel j's own model, the
    // same every row; each channel gets a sixth of the photons, so each is
    // noisier than the whole band.
    let models = channel_models(&inputs(), &six).unwrap();
    let sd = |m: &Model| {
        let e = expectation(&m.calibrated_setup(WINDOW.0), &m.noise, Formula::Exact).unwrap();
        e.var_v1_sq.unwrap().sqrt()
    };
    let per_channel: Vec<f64> = models.iter().map(sd).collect();
    let whole = sd(&Model::new(&inputs()).unwrap());
    assert!(
        per_channel.iter().all(|&s| s > whole),
        "{per_channel:?} vs {whole}"
    );
    let err = vis2.f64_values("VIS2ERR");
    for (i, e) in err.iter().enumerate() {
        assert_eq!(e.to_bits(), per_channel[i % 6].to_bits(), "VIS2ERR {i}");
    }
    // The crate's reader: NWAVE 6, the same wavelengths.
    let tables = read_vis2_tables(&path, "estimates").unwrap();
    assert_eq!((tables[0].nwave, tables[0].rows), (6, ROWS));
    let read_waves: Vec<f32> = tables[0].eff_wave_m.iter().map(|&w| w as f32).collect();
    assert_eq!(read_waves, want);
}

#[test]
fn written_channels_are_read_back_bit_for_bit_in_either_wavelength_order() {
    let dir = tempfile::tempdir().unwrap();
    let six = channels(6);
    let ours = written(dir.path(), &six);
    let waves = eff_waves_m(&six);
    // The plain writer: the set's order (decreasing wavelength), then
    // reversed (increasing), EFF_WAVE as float32 either way.
    let mut files = vec![ours];
    for (name, order) in [
        ("down.fits", [0, 1, 2, 3, 4, 5]),
        ("up.fits", [5, 4, 3, 2, 1, 0]),
    ] {
        let path = dir.path().join(name);
        let eff: Vec<f32> = order.iter().map(|&j| waves[j] as f32).collect();
        let tables: Vec<PlainTable> = ["P_V1", "P_V2"]
            .iter()
            .enumerate()
            .map(|(e, ins)| (*ins, laid_out(e, &order), vec![false; ROWS * 6]))
            .collect();
        plain(&path, Ok(eff), &tables[..1]);
        files.push(path.clone());
        // The V2² table alone, read as V2².
        let v2 = dir.path().join(format!("v2_{name}"));
        plain(
            &v2,
            Ok(order.iter().map(|&j| waves[j] as f32).collect()),
            &tables[1..],
        );
        let got = read(&v2, Some(Estimator::V2Sq), Some(&six));
        for (j, ch) in got.channels.iter().enumerate() {
            let want: Vec<u64> = (0..ROWS).map(|r| value(1, r, j).to_bits()).collect();
            let bits: Vec<u64> = ch
                .estimates
                .v2_sq
                .as_ref()
                .unwrap()
                .iter()
                .map(|x| x.to_bits())
                .collect();
            assert_eq!(bits, want, "{name}, channel {j}");
        }
    }
    for path in &files {
        let got = read(path, Some(Estimator::V1Sq), Some(&six));
        assert_eq!((got.rows, got.flagged, got.channels.len()), (ROWS, 0, 6));
        assert_eq!(got.estimates.v1_sq, None);
        for (j, ch) in got.channels.iter().enumerate() {
            assert_eq!(ch.channel, j);
            assert_eq!(ch.range_m, wavelength_ranges_m(&six)[j]);
            assert_eq!(ch.eff_wave_m as f32, waves[j] as f32);
            let bits: Vec<u64> = ch
                .estimates
                .v1_sq
                .as_ref()
                .unwrap()
                .iter()
                .map(|x| x.to_bits())
                .collect();
            let want: Vec<u64> = (0..ROWS).map(|r| value(0, r, j).to_bits()).collect();
            assert_eq!(bits, want, "{}, channel {j}", path.display());
        }
    }
}

#[test]
fn a_flagged_row_leaves_only_its_channel_for_every_estimator() {
    let dir = tempfile::tempdir().unwrap();
    let six = channels(6);
    let waves = eff_waves_m(&six);
    let order = [5, 4, 3, 2, 1, 0];
    let eff: Vec<f32> = order.iter().map(|&j| waves[j] as f32).collect();
    // Column k holds channel order[k]: flag (row 3, channel 1) in the V1²
    // table and (row 7, channel 4) in the V2² table, the flagged value not
    // a number.
    let col = |j: usize| order.iter().position(|&x| x == j).unwrap();
    let mut v1 = laid_out(0, &order);
    let mut f1 = vec![false; ROWS * 6];
    f1[3 * 6 + col(1)] = true;
    v1[3 * 6 + col(1)] = f64::NAN;
    let mut f2 = vec![false; ROWS * 6];
    f2[7 * 6 + col(4)] = true;
    let tables = [("E_V1", v1, f1), ("E_V2", laid_out(1, &order), f2)];
    let path = dir.path().join("flags.fits");
    plain(&path, Ok(eff), &tables);
    // Two INSNAMEs without V2R_EST: one file per estimator is what a
    // pipeline writes; here both are read by INSNAME.
    let both = |ins: &str, e: Estimator| {
        let choice = Choice {
            insname: Some(ins),
            estimator: Some(e),
            ..Choice::default()
        };
        read_oifits_estimates(&path, &choice, &expected(Some(&six))).unwrap()
    };
    let r1 = both("E_V1", Estimator::V1Sq);
    let kept = |j: usize, left_out: Option<usize>, e: usize| -> Vec<u64> {
        (0..ROWS)
            .filter(|&r| Some(r) != left_out)
            .map(|r| value(e, r, j).to_bits())
            .collect()
    };
    let bits = |x: &Option<Vec<f64>>| -> Vec<u64> {
        x.as_ref().unwrap().iter().map(|v| v.to_bits()).collect()
    };
    for (j, ch) in r1.channels.iter().enumerate() {
        let out = (j == 1).then_some(3);
        assert_eq!(bits(&ch.estimates.v1_sq), kept(j, out, 0), "channel {j}");
        assert_eq!(ch.flagged, usize::from(j == 1));
    }
    assert_eq!(r1.flagged, 1);
    // Across estimators within a channel: the same file with V2R_EST-less
    // tables read together would need one estimator per INSNAME; write
    // both in one table group with v2ref's keywords instead.
    let ours = dir.path().join("ours.fits");
    let mut doc = estimates_doc_channels(
        (&inputs(), &six),
        &columns(6),
        WINDOW,
        &ObservingContext::default(),
    )
    .unwrap();
    doc.tables[0].flag[3 * 6 + 1] = true; // V1², row 3, channel 1
    doc.tables[1].flag[7 * 6 + 4] = true; // V2², row 7, channel 4
    write_oifits(&ours, "out", &doc).unwrap();
    let got = read(&ours, None, Some(&six));
    assert_eq!(got.flagged, 2);
    for (j, ch) in got.channels.iter().enumerate() {
        let out = match j {
            1 => Some(3),
            4 => Some(7),
            _ => None,
        };
        assert_eq!(
            bits(&ch.estimates.v1_sq),
            kept(j, out, 0),
            "V1², channel {j}"
        );
        assert_eq!(
            bits(&ch.estimates.v2_sq),
            kept(j, out, 1),
            "V2², channel {j}"
        );
        assert_eq!(ch.flagged, usize::from(out.is_some()));
    }
}

#[test]
fn each_channels_truth_is_for_its_own_kept_rows() {
    let dir = tempfile::tempdir().unwrap();
    let six = channels(6);
    let ours = dir.path().join("ours.fits");
    let mut doc = estimates_doc_channels(
        (&inputs(), &six),
        &columns(6),
        WINDOW,
        &ObservingContext::default(),
    )
    .unwrap();
    // Ten rows flagged in channel 2: 30 kept of 40.
    for r in 0..10 {
        doc.tables[0].flag[r * 6 + 2] = true;
    }
    write_oifits(&ours, "out", &doc).unwrap();
    let got = read(&ours, None, Some(&six));
    let one = EstimatorTruth {
        mean: 0.5,
        var: 0.01,
        mean_source: TruthSource::ClosedForm,
        var_source: TruthSource::ClosedForm,
        stderr_mean: 0.0,
        stderr_var: 0.0,
        set_stderr_mean: 0.03,
        set_stderr_var: Some(0.002),
        stderr_dof: None,
    };
    let truth = ConventionTruth {
        bias: BiasConvention::Model,
        v1_sq: one,
        v2_sq: one,
    };
    let kept = got.channels[2].truth_for_kept_rows(&truth, ROWS as u64);
    let grown = (40.0f64 / 30.0).sqrt();
    assert_eq!(kept.v1_sq.set_stderr_mean, 0.03 * grown);
    assert_eq!(kept.v2_sq.set_stderr_var, Some(0.002 * grown));
    assert_eq!(
        got.channels[0].truth_for_kept_rows(&truth, ROWS as u64),
        truth
    );
}

#[test]
fn a_file_that_is_not_the_sets_channels_is_refused_saying_what_to_fix() {
    let dir = tempfile::tempdir().unwrap();
    let six = channels(6);
    let waves = eff_waves_m(&six);
    let ranges = wavelength_ranges_m(&six);
    let file = |name: &str, eff: Result<Vec<f32>, Vec<f64>>, flags: Vec<bool>| {
        let path = dir.path().join(name);
        let c = match &eff {
            Ok(w) => w.len(),
            Err(w) => w.len(),
        };
        let vals = (0..ROWS * c).map(|i| value(0, i / c, i % c)).collect();
        plain(&path, eff, &[("PIPE", vals, flags)]);
        path
    };
    let f32s = |w: &[f64]| w.iter().map(|&x| x as f32).collect::<Vec<f32>>();
    let v1 = Some(Estimator::V1Sq);
    let at = "HDU 3 (EXTNAME OI_VIS2, INSNAME PIPE)";
    // NWAVE 6 against a set of 4 channels.
    let p = file("six.fits", Ok(f32s(&waves)), vec![false; ROWS * 6]);
    let m = refusal(&p, v1, Some(&channels(4)));
    assert!(
        m.contains(at) && m.contains("NWAVE = 6, but the set has 4"),
        "{m}"
    );
    // NWAVE 6 without the set's channels: how to score them.
    let m = refusal(&p, v1, None);
    assert!(
        m.contains("NWAVE = 1") && m.contains("same 6 spectral channels"),
        "{m}"
    );
    // An EFF_WAVE in no channel: it and the channels' ranges in µm.
    let mut off = f32s(&waves);
    off[2] = 2.6e-6;
    let m = refusal(
        &file("off.fits", Ok(off), vec![false; ROWS * 6]),
        v1,
        Some(&six),
    );
    assert!(
        m.contains(at) && m.contains("EFF_WAVE 3 of 6 (2.600000 µm) lies in none"),
        "{m}"
    );
    let listed = format!("[{:.6}, {:.6}] µm", ranges[0].0 * 1e6, ranges[0].1 * 1e6);
    assert!(m.contains(&listed), "{m}");
    // Two EFF_WAVE in one channel (and so none in another).
    let mut twice = f32s(&waves);
    twice[3] = waves[2] as f32;
    let m = refusal(
        &file("twice.fits", Ok(twice), vec![false; ROWS * 6]),
        v1,
        Some(&six),
    );
    assert!(
        m.contains("EFF_WAVE 3 and 4") && m.contains("both lie in the set's channel 3 of 6"),
        "{m}"
    );
    // On the edge two channels share: which one is not known.
    let mut edge = waves.clone();
    edge[0] = ranges[0].0;
    assert_eq!(ranges[0].0, ranges[1].1);
    let m = refusal(
        &file("edge.fits", Err(edge), vec![false; ROWS * 6]),
        v1,
        Some(&six),
    );
    assert!(
        m.contains("on the edge of the set's channels 1 and 2"),
        "{m}"
    );
    // A channel with every row flagged, or fewer than half unflagged.
    let floor = min_unflagged_rows(ROWS as u64) as usize;
    for (flagged, ok) in [
        (ROWS, false),
        (ROWS - floor + 1, false),
        (ROWS - floor, true),
    ] {
        let mut flags = vec![false; ROWS * 6];
        for r in 0..flagged {
            flags[r * 6 + 4] = true;
        }
        let p = file("flagged.fits", Ok(f32s(&waves)), flags);
        if ok {
            assert_eq!(read(&p, v1, Some(&six)).channels[4].flagged, flagged);
            continue;
        }
        let m = refusal(&p, v1, Some(&six));
        let said = format!("{} of {ROWS} rows unflagged", ROWS - flagged);
        assert!(
            m.contains(at) && m.contains("channel 5 of 6") && m.contains(&said),
            "{m}"
        );
        assert!(m.contains(&format!("at least {floor}")), "{m}");
    }
    // An unflagged value that is not a number, in its channel.
    let path = dir.path().join("nan.fits");
    let mut vals: Vec<f64> = (0..ROWS * 6).map(|i| value(0, i / 6, i % 6)).collect();
    vals[5 * 6 + 2] = f64::NAN;
    plain(
        &path,
        Ok(f32s(&waves)),
        &[("PIPE", vals, vec![false; ROWS * 6])],
    );
    let m = refusal(&path, v1, Some(&six));
    assert!(m.contains("V1SQ, channel 3, unflagged value 6"), "{m}");
}

#[test]
fn an_eff_wave_rounded_to_float32_or_just_past_an_outer_edge_is_matched() {
    let dir = tempfile::tempdir().unwrap();
    let six = channels(6);
    let ranges = wavelength_ranges_m(&six);
    let mut waves = eff_waves_m(&six);
    let width = |j: usize| ranges[j].1 - ranges[j].0;
    let v1 = Some(Estimator::V1Sq);
    let file = |name: &str, eff: Result<Vec<f32>, Vec<f64>>| {
        let path = dir.path().join(name);
        let vals = (0..ROWS * 6).map(|i| value(0, i / 6, i % 6)).collect();
        plain(&path, eff, &[("PIPE", vals, vec![false; ROWS * 6])]);
        path
    };
    // The outer edges as float32: either side of the edge by rounding.
    waves[0] = ranges[0].1;
    waves[5] = ranges[5].0;
    let rounded: Vec<f32> = waves.iter().map(|&w| w as f32).collect();
    let got = read(&file("f32.fits", Ok(rounded)), v1, Some(&six));
    assert_eq!(got.channels.len(), 6);
    // Past the longest edge by half the slack (1e-4 of the width): read;
    // by twice the slack: in no channel.
    waves[0] = ranges[0].1 + 0.5e-4 * width(0);
    assert_eq!(
        read(&file("in.fits", Err(waves.clone())), v1, Some(&six))
            .channels
            .len(),
        6
    );
    waves[0] = ranges[0].1 + 2e-4 * width(0);
    let m = refusal(&file("out.fits", Err(waves.clone())), v1, Some(&six));
    assert!(
        m.contains("EFF_WAVE 1 of 6") && m.contains("lies in none"),
        "{m}"
    );
}
