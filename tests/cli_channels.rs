//! Spectral channels at the command line (issue 54): `bias`, `snr` and
//! `simulate` answer per channel from `--channels`, `--resolution` or
//! `--channels-csv`, each number the library's own call made here; one
//! channel over the band is the wide band's numbers; the inputs are
//! refused, one line and status 2 naming the flag, where they are wrong
//! or not taken.

use serde_json::Value;
use std::path::Path;
use v2ref_commands::parameters::{ChannelsFile, Physical};
use v2ref_core::bias::channels::channel_biases;
use v2ref_core::formalism::estimator::BinWindow;
use v2ref_core::noise::Formula;
use v2ref_core::simulator::channels::{channel_expectations, channel_models};

use crate::run::v2ref;
use v2ref_core::assert_rel_eq;
use v2ref_core::tolerance::ULPS;

/// `got` (read back from the CLI's JSON text) is `want`: to the ulp that
/// serde_json's reading of a decimal may add (its default parser is not
/// correctly rounded).
fn same(got: &Value, want: f64) {
    let got = got
        .as_f64()
        .unwrap_or_else(|| panic!("{got} is not a number"));
    assert_rel_eq!(got, want, ULPS);
}

/// Every number of the object `want` (the library's answer serialized)
/// is the same field of `got` ([`same`]).
fn same_fields(got: &Value, want: &Value, what: &str) {
    let want = want.as_object().unwrap_or_else(|| panic!("{what}: {want}"));
    assert_eq!(got.as_object().unwrap().len(), want.len(), "{what}");
    for (k, w) in want {
        same(&got[k], w.as_f64().unwrap());
    }
}

fn json(args: &[&str]) -> Value {
    let (code, out, err) = v2ref(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).expect("one JSON document")
}

/// `args` refused: status 2, one line on stderr naming each of `names`.
fn refused(args: &[&str], names: &[&str]) -> String {
    let (code, out, err) = v2ref(args);
    assert_eq!(code, 2, "{args:?}: {out}{err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    for n in names {
        assert!(err.contains(n), "{args:?}: {err} does not name {n}");
    }
    assert!(out.is_empty(), "{args:?}: nothing on stdout, got {out}");
    err
}

/// With one channel over the whole band, `bias` answers the wide band's
/// numbers: every field of the run without channels the same, and the
/// channel's own numbers the wide band's bits, with all the photons.
#[test]
fn one_channel_over_the_band_is_the_wide_band() {
    let args = [
        "bias",
        "--finite-scan",
        "--dispersion-pp-rad",
        "3",
        "--json",
    ];
    let wide = json(&args);
    let one = json(&[&args[..], &["--channels", "1"]].concat());
    let mut without = one.clone();
    let channels = without.as_object_mut().unwrap().remove("channels").unwrap();
    assert_eq!(without, wide);
    let line = &channels.as_array().unwrap()[0];
    assert_eq!(channels.as_array().unwrap().len(), 1);
    assert_eq!(line["photon_share"], 1.0);
    for k in ["v_mono", "v1", "v2", "v1_sq", "v2_sq", "sigma_eff_per_um"] {
        assert_eq!(line["wide_band"][k], wide[k], "{k}");
    }
    // The dispersion bias is the wide band's V with minus without phase.
    let flat = json(&["bias", "--json"]);
    let d = line["dispersion"]["v1"].as_f64().unwrap();
    let want = wide["v1"].as_f64().unwrap() - flat["v1"].as_f64().unwrap();
    assert_eq!(d, want);
}

/// The configuration of the per-channel tests: K band with dispersion
/// and an integrating detector, so that every bias term is non-zero.
const CONFIG: [&str; 3] = ["--dispersion-pp-rad", "2", "--integrating"];

fn physical() -> Physical {
    Physical {
        dispersion_pp_rad: 2.0,
        integrating: true,
        read_noise: 1.0,
        ..Physical::DEFAULT
    }
}

/// `bias --channels 4`: each line's biases are `channel_biases` of the
/// same configuration, bit for bit, and its place the channels' own.
#[test]
fn bias_per_channel_is_the_library_call() {
    let v = json(&[&["bias"][..], &CONFIG[..], &["--channels", "4", "--json"]].concat());
    let p = Physical {
        channels: Some(4),
        ..physical()
    };
    let channels = p.channels().unwrap().unwrap();
    let want =
        channel_biases(&p.observation().unwrap(), &channels, &p.sampling().unwrap()).unwrap();
    let lines = v["channels"].as_array().unwrap();
    assert_eq!(lines.len(), 4);
    for (j, (line, b)) in lines.iter().zip(&want).enumerate() {
        let b = serde_json::to_value(b).unwrap();
        for k in [
            "wide_band",
            "bandwidth",
            "dispersion",
            "finite_scan",
            "integrating",
        ] {
            same_fields(&line[k], &b[k], &format!("channel {}: {k}", j + 1));
            // (V1 does not see the phase: the dispersion moves V2 alone.)
            assert_ne!(line[k]["v2"], 0.0, "channel {}: {k} is tested", j + 1);
        }
        let (lo, hi) = channels.edges_per_um()[j];
        same(&line["wavenumber_lo_per_um"], lo);
        same(&line["wavelength_lo_um"], 1.0 / hi);
        same(&line["photon_share"], channels.photon_shares()[j]);
    }
    let (code, table, _) = v2ref(&["bias", "--channels", "4"]);
    assert_eq!(code, 0);
    assert_eq!(table.lines().filter(|l| l.contains("0.2500")).count(), 4);
}

/// `snr --channels 3`: each channel's mean and σ are
/// `channel_expectations`'; the combination is the photon-weighted mean
/// with σ = √(Σ q_j² σ_j²), and says the piston correlates channels.
#[test]
fn snr_per_channel_is_the_library_call_and_the_combination_is_stated() {
    let args = [
        &["snr"][..],
        &CONFIG[..],
        &["--read-noise", "1", "--channels", "3", "--json"],
    ]
    .concat();
    let v = json(&args);
    let p = Physical {
        channels: Some(3),
        ..physical()
    };
    let channels = p.channels().unwrap().unwrap();
    let models = channel_models(&p.inputs().unwrap(), &channels).unwrap();
    let want = channel_expectations(&models, BinWindow::Positive, Formula::Exact).unwrap();
    let lines = v["channels"].as_array().unwrap();
    let q = channels.photon_shares();
    let (mut mean, mut var) = (0.0, 0.0);
    for (j, (line, e)) in lines.iter().zip(&want).enumerate() {
        let sigma = e.var_v1_sq.unwrap().sqrt();
        same(&line["v1_sq"]["mean"], e.mean_v1_sq);
        same(&line["v1_sq"]["sigma"], sigma);
        same(&line["v2_sq"]["mean"], e.mean_v2_sq);
        same(&line["v2_sq"]["sigma"], e.var_v2_sq.unwrap().sqrt());
        same(&line["v1_sq"]["snr"], e.mean_v1_sq / sigma);
        mean += q[j] * e.mean_v1_sq;
        var += (q[j] * sigma).powi(2);
    }
    assert_eq!(lines.len(), 3);
    let c = &v["combined"];
    same(&c["v1_sq"]["mean"], mean);
    same(&c["v1_sq"]["sigma"], var.sqrt());
    let words = format!("{} {}", c["weights"], c["note"]);
    for w in ["photon-weighted", "independent", "piston", "simulate"] {
        assert!(words.contains(w), "{words}");
    }
    // The wide band's numbers are still there, as without channels.
    let wide = json(&[&["snr"][..], &CONFIG[..], &["--read-noise", "1", "--json"]].concat());
    assert_eq!(v["snr1"], wide["snr1"]);
}

/// A 6-channel H-band `simulate` with the piston dominating: the
/// channels' errors correlate (every correlation > 0), so the combination's
/// measured σ exceeds the σ of independent channels; the combination's
/// mean is the photon-weighted mean of the channels' means.
#[test]
fn simulate_with_piston_correlates_the_channels() {
    let v = json(&[
        "simulate",
        "--channels",
        "6",
        "--wavelength-um",
        "1.65",
        "--bandwidth-nm",
        "300",
        "--dx-um",
        "0.4",
        "--samples",
        "256",
        "--fringe-hz",
        "300",
        "--photons",
        "1000",
        "--no-photon-noise",
        "--bias",
        "counts",
        "--trials",
        "1500",
        "--seed",
        "7",
        "--quiet",
        "--json",
    ]);
    let lines = v["channels"].as_array().unwrap();
    assert_eq!(lines.len(), 6);
    for name in ["combined_v1_sq", "combined_v2_sq"] {
        let c = &v[name];
        let rho = c["correlation"].as_array().unwrap();
        assert_eq!(rho.len(), 6);
        for (i, row) in rho.iter().enumerate() {
            for (j, x) in row.as_array().unwrap().iter().enumerate() {
                let x = x.as_f64().unwrap();
                assert!(x > 0.0, "{name}: correlation {i},{j} = {x}");
            }
        }
        let (sigma, independent) = (
            c["sigma"].as_f64().unwrap(),
            c["independent_sigma"].as_f64().unwrap(),
        );
        assert!(sigma > independent, "{name}: {sigma} vs {independent}");
        same(&c["sigma_ratio"], sigma / independent);
        let key = &name["combined_".len()..];
        let mean: f64 = lines
            .iter()
            .map(|l| l["photon_share"].as_f64().unwrap() * l[key]["mean"].as_f64().unwrap())
            .sum();
        same(&c["mean"], mean);
    }
    assert!(v["note"].as_str().unwrap().contains("sqrt(C)"));
}

/// Two channel inputs at once are refused naming both; so is each bad
/// value, naming the flag given.
#[test]
fn bad_or_double_channel_inputs_are_refused_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.csv");
    std::fs::write(
        &good,
        "wavelength_lo_um,wavelength_hi_um,response\n2.0,2.2,1\n2.2,2.4,2\n",
    )
    .unwrap();
    let good = good.to_str().unwrap();
    refused(
        &["bias", "--channels", "2", "--resolution", "20"],
        &["--channels", "resolution"],
    );
    refused(
        &["snr", "--channels-csv", good, "--resolution", "20"],
        &["--resolution", "channels_csv"],
    );
    refused(&["bias", "--channels", "0"], &["--channels", "4096"]);
    refused(&["bias", "--channels", "4097"], &["--channels", "4096"]);
    refused(&["bias", "--channels", "2.5"], &["--channels"]);
    refused(&["bias", "--resolution", "-3"], &["--resolution"]);
    // 128 samples of 0.5 µm resolve about 5 channels of the K band.
    refused(
        &["bias", "--resolution", "100"],
        &["--resolution", "DFT bin"],
    );
    refused(&["snr", "--channels", "12"], &["--channels", "DFT bin"]);
    let rows = [
        ("overlap", "2.0,2.25,1\n2.2,2.4,1\n", "overlap"),
        ("unordered", "2.2,2.4,1\n2.0,2.2,1\n", "out of order"),
        ("outside", "1.5,2.2,1\n2.2,2.4,1\n", "outside the band"),
        ("header", "", "no header"),
    ];
    for (name, body, why) in rows {
        let path = dir.path().join(format!("{name}.csv"));
        let head = if body.is_empty() {
            ""
        } else {
            "wavelength_lo_um,wavelength_hi_um,response\n"
        };
        std::fs::write(&path, format!("{head}{body}")).unwrap();
        let path = path.to_str().unwrap();
        refused(
            &["bias", "--channels-csv", path],
            &["--channels-csv", why, path],
        );
    }
    let err = refused(
        &["bias", "--channels-csv", "/no/such.csv"],
        &["--channels-csv"],
    );
    assert!(err.contains("/no/such.csv"), "{err}");
}

/// The channel table is read by the project's reader: a FIFO is refused
/// at once (never waited on), a link the user gave is followed, its
/// answer the file's own; the table's responses set the photon shares.
#[test]
fn the_channel_table_is_read_as_every_input_file() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("fifo.csv");
    let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a NUL-terminated path that lives through the call.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o666) }, 0);
    refused(
        &["bias", "--channels-csv", fifo.to_str().unwrap()],
        &["--channels-csv", "FIFO"],
    );
    let file = dir.path().join("two.csv");
    let text = "wavelength_lo_um,wavelength_hi_um,response\n2.0,2.2,1\n2.2,2.4,3\n";
    std::fs::write(&file, text).unwrap();
    let link = dir.path().join("link.csv");
    std::os::unix::fs::symlink(&file, &link).unwrap();
    let by_file = json(&["bias", "--channels-csv", file.to_str().unwrap(), "--json"]);
    let by_link = json(&["bias", "--channels-csv", link.to_str().unwrap(), "--json"]);
    assert_eq!(by_file["channels"], by_link["channels"]);
    let p = Physical {
        channels_csv: Some(ChannelsFile::new(Path::new("two.csv"), text.into())),
        ..Physical::DEFAULT
    };
    let shares = p.channels().unwrap().unwrap().photon_shares().to_vec();
    let lines = by_file["channels"].as_array().unwrap();
    // A flat band: each channel's light is its width in wavenumber times
    // its response; channel 1 is 2.2-2.4 µm, response 3.
    let light = [3.0 * (1.0 / 2.2 - 1.0 / 2.4), 1.0 / 2.0 - 1.0 / 2.2];
    for (j, (line, q)) in lines.iter().zip(&shares).enumerate() {
        assert_rel_eq!(*q, light[j] / (light[0] + light[1]));
        same(&line["photon_share"], *q);
    }
}

/// Commands that do not take channels yet refuse them, naming the flag
/// and the command, before any work.
#[test]
fn commands_without_channels_refuse_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("set");
    let out = out.to_str().unwrap();
    let cases: [&[&str]; 5] = [
        &["plan", "--channels", "2"],
        &["piston", "--resolution", "20", "--scans", "2"],
        &["synth", "--channels", "2", "--out", out],
        &["estimate", "--channels", "2", "--input", "/no/such.npy"],
        &[
            "simulate",
            "--channels",
            "2",
            "--formula",
            "published",
            "--trials",
            "8",
        ],
    ];
    for args in cases {
        let names = match args[0] {
            "simulate" => vec!["--formula", "exact"],
            command => vec![args[1], "not taken by", command],
        };
        refused(args, &names);
    }
    assert!(
        std::fs::read_dir(dir.path()).unwrap().next().is_none(),
        "nothing written"
    );
}
