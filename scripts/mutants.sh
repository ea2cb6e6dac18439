#!/usr/bin/env bash
# Mutation testing of the numeric core, one area at a time, each with the
# test files that verify it (docs/mutation.md, tests/README.md): modules of
# the one test binary tests/suite.rs, chosen by libtest filters (`NAME::`).
#
#   scripts/mutants.sh AREA [AREA ...] [-- extra cargo-mutants options]
#   scripts/mutants.sh all
#   scripts/mutants.sh estimators -- --in-place   # reuse the tree's target dir
#   RECHECK=missed.txt scripts/mutants.sh special  # only the named mutants
#   FIRST_PASS_ONLY=1 scripts/mutants.sh piston_spectrum  # no second pass
#
# Two passes per area. The first skips the area's slow tests (SLOW below:
# long sampled scans and Monte Carlo runs, 3–30 s each at opt-level 0) and
# reports into mutants.out/AREA/; the second reruns only the mutants the
# first missed, with every test of the area, into mutants.out/AREA/full/.
# A mutant is caught by the suite when either pass catches it, and missed
# only when it survives the second pass.
#
# With FIRST_PASS_ONLY set, the second pass is left out: the first pass's
# misses are then the list to write tests for (and to RECHECK after).
#
# With RECHECK set to a file of mutant names (a missed.txt of an earlier
# run), only the area's mutants named there are run, in the same two
# passes, into mutants.out/AREA-recheck/: the check after adding tests.
#
# Each area writes its report to mutants.out/AREA/ (git-ignored). The
# configuration shared by all areas (scope, opt-level, timeouts) is in
# .cargo/mutants.toml.
set -euo pipefail

# AREA -> "file globs | test files (modules of tests/suite.rs)"
declare -A AREAS=(
    [estimators]="crates/v2ref-core/src/formalism/estimator.rs|spectral_estimators foundation"
    [statistics]="crates/v2ref-core/src/montecarlo/statistics.rs|running_stats montecarlo_noise"
    [seeding]="crates/v2ref-core/src/montecarlo/mod.rs|montecarlo_noise noise_mc golden"
    [special]="crates/v2ref-core/src/math/special/*.rs crates/v2ref-core/src/math/quadrature.rs|special foundation bias_dispersion"
    [spectrum]="crates/v2ref-core/src/formalism/spectrum.rs crates/v2ref-core/src/formalism/source.rs|spectral_estimators foundation spectrum_csv bias_line"
    [interferogram]="crates/v2ref-core/src/formalism/interferogram.rs crates/v2ref-core/src/formalism/oracle.rs crates/v2ref-core/src/formalism/phase.rs|foundation bias_finite_scan properties"
    [noise]="crates/v2ref-core/src/noise/window_variance.rs crates/v2ref-core/src/noise/appendix.rs crates/v2ref-core/src/noise/calibrated.rs crates/v2ref-core/src/noise/model.rs|noise noise_calibrated montecarlo_noise"
    [noise_simulation]="crates/v2ref-core/src/noise/simulation.rs|noise_mc montecarlo_noise"
    [dispersion]="crates/v2ref-core/src/bias/dispersion.rs|bias_dispersion"
    [finite_scan]="crates/v2ref-core/src/bias/finite_scan.rs crates/v2ref-core/src/bias/normalization.rs crates/v2ref-core/src/bias/bandwidth.rs|bias_finite_scan bias_normalization bias_bandwidth"
    [turbulence]="crates/v2ref-core/src/piston/turbulence.rs|turbulence piston"
    [piston_spectrum]="crates/v2ref-core/src/piston/spectrum.rs crates/v2ref-core/src/piston/transverse.rs|piston_spectrum turbulence piston"
    [fft]="crates/v2ref-core/src/math/fft.rs|fft"
)

# AREA -> tests (libtest name filters) left out of the first pass: each
# takes 1–30 s at opt-level 0 where the rest of the area takes about one.
# (the sampled-versus-spectral comparisons of foundation and spectral_estimators)
SLOW_SCANS="long_finely_sampled_scans_converge long_sampled_scans_agree spectral_estimators_match_an_independent_quadrature v2_sq_is_bounded_by_the_w_weighted_mean"
# (the tests of turbulence and piston that build the transverse table: 6–28 s
# each at opt-level 0)
SLOW_PISTON="middle_asymptote_is_the_period_average real_tables_hold cli_seeing_wavelength_flag table_matches_direct_quadrature the_table_of_g_matches_mpmath variance_is_the_integral_of_the_temporal wind_across_the_baseline wind_angle_zero a_sweep_at_1000_hz a_sweep_frequency_does_not centred_all_bins_v2 lag_structure_function periodogram_matches piston_is_multiplicative piston_monte_carlo_is_deterministic sample_variance_matches series_are_deterministic three_slope_series wind_speed_rescales zero_turbulence_gives"
# (the Monte Carlo runs of noise_mc: 8–26 s each at opt-level 0; golden's
# regeneration of every figure: minutes)
SLOW_MC="windowed_variance_gaussian_two_windows windowed_variance_photon_third_and_fourth all_bins_expectations_biases_and_variances"
declare -A SLOW=(
    [estimators]="$SLOW_SCANS"
    [special]="long_finely_sampled_scans_converge"
    [spectrum]="$SLOW_SCANS"
    [interferogram]="long_finely_sampled_scans_converge long_sampled_scans_agree long_scans_reproduce the_bias_vanishes_as_the_stroke_grows"
    [noise]="poisson_samplers_follow_the_poisson_law"
    [noise_simulation]="$SLOW_MC"
    [seeding]="$SLOW_MC golden_data_matches_the_code cli_check_names_each_mismatch"
    [finite_scan]="long_scans_reproduce the_bias_vanishes_as_the_stroke_grows the_factor_tends_to_one_with_the_stroke wide_band_loss_matches_synthesized"
    [fft]="four_step_equals_one_rustfft_transform_at_the_fig5_length same_bits_on_any_number_of_threads"
    [piston_spectrum]="$SLOW_PISTON"
    [turbulence]="$SLOW_PISTON"
)
ORDER=(estimators statistics special spectrum noise interferogram dispersion finite_scan turbulence piston_spectrum noise_simulation seeding fft)

areas=()
while [[ $# -gt 0 && $1 != "--" ]]; do
    if [[ $1 == all ]]; then areas+=("${ORDER[@]}"); else areas+=("$1"); fi
    shift
done
[[ ${1:-} == "--" ]] && shift
if [[ ${#areas[@]} -eq 0 ]]; then
    echo "usage: $0 AREA... | all  [-- cargo-mutants options]; areas: ${ORDER[*]}" >&2
    exit 2
fi

# The mutant names listed in file $1, escaped for cargo-mutants' regex
# filter, anchored, one alternative each.
anchored() {
    sed -e 's/[][\\.*^$(){}+?|]/\\&/g' -e 's/^/^/' -e 's/$/$/' "$1" | paste -sd'|'
}

for area in "${areas[@]}"; do
    spec=${AREAS[$area]:-}
    if [[ -z $spec ]]; then
        echo "unknown area '$area'; areas: ${ORDER[*]}" >&2
        exit 2
    fi
    files=() filters=()
    for f in ${spec%%|*}; do files+=(--file "$f"); done
    # --cargo-arg, not "-- --test": cargo-mutants passes arguments after
    # "--" to the test run only, and would also build the library's unit
    # tests and the examples. The suite needs the binary (the default
    # features) as some of its files run it. The mutated files are the
    # numerics' (package v2ref-core), the suite the root
    # package's (v2ref-cli): mutate the workspace, test the workspace.
    tests=(--workspace --test-workspace=true --cargo-arg=--test=suite)
    for t in ${spec##*|}; do filters+=("$t::"); done
    echo "== $area: ${spec%%|*} with ${spec##*|}"
    out="mutants.out/$area"
    only=()
    if [[ -n ${RECHECK:-} ]]; then
        out="mutants.out/$area-recheck"
        only=(--re "$(anchored "$RECHECK")")
    fi
    mkdir -p "$out"
    skips=()
    for t in ${SLOW[$area]:-}; do skips+=(--skip "$t"); done
    # cargo-mutants appends what follows its "--" to `cargo test`, so the
    # libtest filters need a second "--".
    harness=(-- -- "${filters[@]}" "${skips[@]}")
    cargo mutants "${files[@]}" "${tests[@]}" --output "$out" "${only[@]}" "$@" "${harness[@]}" || true

    missed="$out/mutants.out/missed.txt"
    if [[ -z ${FIRST_PASS_ONLY:-} && ${#skips[@]} -gt 0 && -s $missed ]]; then
        re=$(anchored "$missed")
        echo "== $area, second pass: $(wc -l < "$missed") missed mutants with every test"
        mkdir -p "$out/full"
        # A shard of the first pass is already a subset: the second runs
        # all of its misses.
        rest=()
        skip_next=0
        for a in "$@"; do
            if [[ $skip_next == 1 ]]; then skip_next=0; continue; fi
            case $a in
                --shard) skip_next=1 ;;
                --shard=*) ;;
                *) rest+=("$a") ;;
            esac
        done
        cargo mutants "${files[@]}" "${tests[@]}" --output "$out/full" --re "$re" "${rest[@]}" -- -- "${filters[@]}" || true
    fi
done
