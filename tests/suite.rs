//! The integration tests, one module per file of `tests/` and one test
//! binary for them all: linked once instead of once per file (the build of
//! the tests was mostly linking), and run together, so that a long test of
//! one file overlaps with the others instead of holding the suite up.
//!
//! Run one file's tests with `cargo test --release --test suite -- NAME::`
//! (for example `-- golden::`); the slow tier (tests marked
//! `#[ignore = "slow tier: ..."]`) with `cargo test --release --test suite
//! -- --ignored`. A new file of `tests/` is a module declared here (the test
//! `every_file_of_tests_is_a_module_of_the_suite` fails otherwise: Cargo
//! builds no other test binary, `autotests = false`).

mod architecture;
mod bias_bandwidth;
mod bias_dispersion;
mod bias_finite_scan;
mod bias_line;
mod bias_normalization;
mod bias_snapshots;
mod cancel;
mod channels;
mod channels_mc;
mod claims;
mod claims_notes;
mod cli;
mod cli_channels;
mod cli_noise;
mod cli_piston;
mod cli_support;
mod commands_estimate;
mod conformance_channels;
mod conformance_cli;
mod conformance_files;
mod conformance_score;
mod conformance_truth;
mod examples;
mod fft;
mod figures_render;
mod fits_plain;
mod foundation;
mod golden;
mod montecarlo_noise;
mod noise;
mod noise_calibrated;
mod noise_cumulants;
mod noise_mc;
mod oifits;
mod oifits_fuzz;
mod oifits_robustness;
mod oifits_rules;
mod oifits_setting;
mod oracle;
mod piston;
mod piston_claims;
mod piston_errors;
mod piston_models;
mod piston_spectrum;
mod plan;
mod plan_cases;
mod plan_check;
mod plan_observation;
mod plan_presets;
mod plan_stability;
mod plan_targets;
mod properties;
mod public_misuse;
mod readme;
mod reproduce;
mod robustness_cli;
mod robustness_commit;
mod robustness_files;
mod robustness_lib;
mod robustness_limits;
mod robustness_memory;
mod robustness_readers;
mod robustness_sets;
mod run;
mod running_stats;
mod security_locks;
mod security_readers;
mod security_sets;
mod security_small;
mod simulator;
mod special;
mod spectral_estimators;
mod spectrum_csv;
mod surface_properties;
mod surface_properties_sets;
mod synth_layout;
mod targets_errors;
mod tolerance_literals;
mod turbulence;
// Issue 53/54, OIFITS read as pipelines write and edit it.
mod oifits_as_written;
mod oifits_channels;
mod oifits_channels_files;

/// Cargo builds only this binary (`autotests = false` in Cargo.toml): a
/// file of `tests/` not declared above would be silently skipped.
#[test]
fn every_file_of_tests_is_a_module_of_the_suite() {
    let this = include_str!("suite.rs");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        if let Some(module) = name.strip_suffix(".rs") {
            if module != "suite" {
                assert!(
                    this.contains(&format!("\nmod {module};\n")),
                    "tests/{name} is not declared in tests/suite.rs: its tests would not run"
                );
            }
        }
    }
}
mod robustness_surface;
