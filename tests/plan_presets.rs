//! `plan --instrument NAME`: every preset lies inside the parameters'
//! accepted ranges (the plan accepts it as it stands), and each kind of
//! flag given overrides the preset's value while a flag left out keeps it.

use crate::run::v2ref;
use v2ref_commands::commands::plan::{prepare, PlanRequest};
use v2ref_commands::parameters::Physical;
use v2ref_commands::plan::instrument::{
    fringe_grid_hz, instrument, Instrument, INSTRUMENTS, PRESET_KEYS,
};
use v2ref_commands::plan::photometry::{Band2Mass, Magnitude};
use v2ref_core::conformance::estimate::BiasConvention;

/// A plan request as the CLI's defaults make it, with a magnitude (whose
/// throughput the preset sets) in `band`.
fn request(band: Band2Mass) -> PlanRequest {
    PlanRequest {
        samples_per_fringe: 4.0,
        photon_rate_per_s: 1e6,
        magnitude: Some(Magnitude {
            magnitude: 5.0,
            band,
            aperture_m: 0.45,
            throughput: f64::NAN,
        }),
        dead_time_s: 0.0,
        frame_rate_hz: None,
        fringe_hz: Vec::new(),
        stroke_um: Vec::new(),
        target_sigma_v2: Some(1e-3),
        time_budget_s: None,
        scans: 16000,
        seed: 1,
        diameter_err_mas: 0.0,
        bias: BiasConvention::Counts,
    }
}

/// The 2MASS or Johnson–Cousins band that covers a preset's band centre.
fn band_of(i: &Instrument) -> Band2Mass {
    match i.wavelength_um {
        w if w < 1.0 => Band2Mass::R,
        w if w < 2.0 => Band2Mass::H,
        _ => Band2Mass::Ks,
    }
}

/// The preset applied to the defaults, no flag given.
fn applied(i: &Instrument) -> (Physical, PlanRequest) {
    let mut p = Physical::default();
    let mut req = request(band_of(i));
    i.apply(&mut p, &mut req, &|_| false);
    (p, req)
}

/// Every preset, applied to the defaults with nothing given, is a plan the
/// library accepts (every input and the plan's own inputs checked, its
/// fringe grid included), its baseline inside its array's range and its
/// grid ending at the detector's edge.
#[test]
fn every_preset_is_inside_the_accepted_ranges() {
    assert!(INSTRUMENTS.len() >= 6);
    for i in &INSTRUMENTS {
        let (p, req) = applied(i);
        let prepared = prepare(&p, &req).unwrap_or_else(|e| panic!("{}: {e}", i.name));
        assert!(i.baseline_min_m <= i.baseline_m && i.baseline_m <= i.baseline_max_m);
        assert!(
            (0.0..=1.0).contains(&i.throughput) && i.throughput > 0.0,
            "{}",
            i.name
        );
        assert!(i.frame_rate_hz > 0.0 && i.read_noise >= 0.0 && i.dead_time_s >= 0.0);
        let grid = &prepared.inputs.fringe_hz;
        let edge = i.frame_rate_hz / 4.0;
        // tol: the log grid's last point is exp(ln(edge)): a few roundings.
        assert!(
            // tol: the log grid's last point is exp(ln(edge)): a few roundings.
            (grid[grid.len() - 1] - edge).abs() <= 1e-12 * edge,
            "{}: {grid:?}",
            i.name
        );
        assert_eq!(instrument(&i.name.to_uppercase()).unwrap(), i);
    }
    let e = instrument("keck").unwrap_err().to_string();
    assert!(e.contains("instrument") && e.contains("npoi"), "{e}");
}

/// Each kind of value a preset sets is overridden by its parameter when
/// given, and kept otherwise: one key given at a time, every other value
/// stays the preset's.
#[test]
fn a_given_parameter_overrides_each_kind_of_preset_value() {
    let i = instrument("vlti-pionier").unwrap();
    let (kept_p, kept_req) = applied(i);
    for key in PRESET_KEYS {
        // The caller's own values, as the flags would have set them.
        let mut p = Physical {
            wavelength_um: 1.6,
            bandwidth_nm: 100.0,
            aperture_m: 8.2,
            baseline_m: Some(33.0),
            read_noise: 7.0,
            ..Physical::default()
        };
        let mut req = request(Band2Mass::H);
        req.dead_time_s = 0.0;
        req.frame_rate_hz = Some(500.0);
        req.fringe_hz = Vec::new();
        if let Some(m) = req.magnitude.as_mut() {
            m.throughput = 0.3;
        }
        if key == "fringe_hz" {
            req.fringe_hz = vec![123.0];
        }
        i.apply(&mut p, &mut req, &|k| k == key);
        let m = req.magnitude.unwrap();
        let got = [
            ("wavelength_um", p.wavelength_um, 1.6, kept_p.wavelength_um),
            ("bandwidth_nm", p.bandwidth_nm, 100.0, kept_p.bandwidth_nm),
            ("aperture_m", p.aperture_m, 8.2, kept_p.aperture_m),
            (
                "baseline_m",
                p.baseline_m.unwrap(),
                33.0,
                kept_p.baseline_m.unwrap(),
            ),
            ("read_noise", p.read_noise, 7.0, kept_p.read_noise),
            ("dead_time_s", req.dead_time_s, 0.0, kept_req.dead_time_s),
            ("throughput", m.throughput, 0.3, i.throughput),
            // The frame rate given moves the grid's edge (issue 55).
            (
                "fringe_hz",
                req.fringe_hz[0],
                123.0,
                if key == "frame_rate_hz" {
                    fringe_grid_hz(500.0 / 4.0)[0]
                } else {
                    kept_req.fringe_hz[0]
                },
            ),
            (
                "frame_rate_hz",
                req.frame_rate_hz.unwrap(),
                500.0,
                i.frame_rate_hz,
            ),
        ];
        for (name, value, own, preset) in got {
            let want = if name == key { own } else { preset };
            assert_eq!(value, want, "{key} given: {name}");
        }
        // The magnitude's apertures are the ones planned with.
        assert_eq!(m.aperture_m, p.aperture_m, "{key} given");
    }
    // A baseline given as a spatial frequency is a baseline given.
    let mut p = Physical {
        spatial_freq_cpas: Some(40.0),
        ..Physical::default()
    };
    i.apply(&mut p, &mut request(Band2Mass::H), &|k| {
        k == "spatial_freq_cpas"
    });
    assert_eq!((p.spatial_freq_cpas, p.baseline_m), (Some(40.0), None));
}

/// A frame rate given with a preset sets the edge of the preset's grid
/// (issue 55: a 2000 Hz detector given to the 1000 Hz MIRC-X preset never
/// searched above 250 Hz): the prepared grid ends at the given rate over
/// the samples per fringe, for a faster and a slower detector, and at the
/// preset's own rate when none is given.
#[test]
fn a_given_frame_rate_sets_the_edge_of_a_presets_grid() {
    let i = instrument("chara-mirc-x").unwrap();
    for (given, spf, edge_hz) in [
        (Some(2000.0), 4.0, 500.0),
        (Some(2000.0), 5.0, 400.0),
        (Some(400.0), 4.0, 100.0),
        (None, 4.0, i.frame_rate_hz / 4.0),
    ] {
        let mut p = Physical::default();
        let mut req = request(Band2Mass::H);
        req.frame_rate_hz = given;
        req.samples_per_fringe = spf;
        i.apply(&mut p, &mut req, &|k| {
            given.is_some() && k == "frame_rate_hz"
        });
        let prepared = prepare(&p, &req).unwrap();
        let grid = &prepared.inputs.fringe_hz;
        let top = grid.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(
            // tol: the log grid's last point is exp(ln(edge)): a few roundings.
            (top - edge_hz).abs() <= 1e-12 * edge_hz,
            "{given:?}: {grid:?}"
        );
        assert_eq!(grid.len(), 20, "{given:?}: {grid:?}");
        assert_eq!(
            prepared.inputs.frame_rate_hz,
            given.or(Some(i.frame_rate_hz))
        );
    }
}

/// The command line: a flag given overrides the preset even at its
/// default value, and a flag left out keeps it — seen in the refusals
/// that name the value in use (no plan is computed).
#[test]
fn the_command_line_overrides_the_preset() {
    let plan = |extra: &[&str]| {
        let mut args = vec!["plan", "--quiet", "--instrument", "npoi"];
        args.extend_from_slice(extra);
        v2ref(&args)
    };
    // The preset's band centre (0.65 µm) is in use: Ks does not cover it.
    let (code, _, err) = plan(&["--magnitude", "2", "--magnitude-band", "ks"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("centred on 0.65 um"), "{err}");
    // Given, --wavelength-um replaces it.
    let (code, _, err) = plan(&[
        "--wavelength-um",
        "2.2",
        "--magnitude",
        "2",
        "--magnitude-band",
        "v",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("centred on 2.2 um"), "{err}");
    // A flag out of range is refused, not replaced by the preset's value.
    let (code, _, err) = plan(&["--aperture-m", "0"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--aperture-m"), "{err}");
    let (code, _, err) = plan(&["--dead-time-s", "-1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--dead-time-s"), "{err}");
    // Without a preset, --magnitude needs --throughput; with one it has it.
    let (code, _, err) = v2ref(&["plan", "--magnitude", "5", "--magnitude-band", "h"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--throughput"), "{err}");
    let (code, out, err) = v2ref(&["plan", "--instrument", "list"]);
    assert_eq!(code, 0, "{err}");
    for i in &INSTRUMENTS {
        assert!(out.contains(i.name), "{out}");
    }
    let (code, _, err) = v2ref(&["plan", "--instrument", "keck"]);
    assert_eq!(code, 2, "{err}");
}
