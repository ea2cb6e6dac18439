#!/usr/bin/env bash
# Mutation testing of the numeric core, one area at a time, each with the
# test binaries that verify it (docs/mutation.md, tests/README.md).
#
#   scripts/mutants.sh AREA [AREA ...] [-- extra cargo-mutants options]
#   scripts/mutants.sh all
#   scripts/mutants.sh estimators -- --in-place   # reuse the tree's target dir
#
# Each area writes its report to mutants.out/AREA/ (git-ignored). The
# configuration shared by all areas (scope, opt-level, timeouts) is in
# .cargo/mutants.toml.
set -euo pipefail

# AREA -> "file globs | test binaries"
# (an area whose tests do not run the v2ref binary is built without the
# default "cli" feature: no binary to link and a fifth less of the crate to
# compile per mutant; NEEDS_CLI lists the others)
declare -A AREAS=(
    [estimators]="src/formalism/estimator.rs|spectral_estimators foundation"
    [statistics]="src/montecarlo/statistics.rs|running_stats montecarlo_noise"
    [seeding]="src/montecarlo/mod.rs|montecarlo_noise noise_mc golden"
    [special]="src/math/special/*.rs src/math/quadrature.rs|special foundation bias_dispersion"
    [spectrum]="src/formalism/spectrum.rs src/formalism/source.rs|spectral_estimators foundation spectrum_csv bias_line"
    [interferogram]="src/formalism/interferogram.rs src/formalism/oracle.rs src/formalism/phase.rs|foundation bias_finite_scan properties"
    [noise]="src/noise/window_variance.rs src/noise/appendix.rs src/noise/calibrated.rs src/noise/model.rs|noise noise_calibrated montecarlo_noise"
    [noise_simulation]="src/noise/simulation.rs|noise_mc montecarlo_noise"
    [dispersion]="src/bias/dispersion.rs|bias_dispersion"
    [finite_scan]="src/bias/finite_scan.rs src/bias/normalization.rs src/bias/bandwidth.rs|bias_finite_scan bias_normalization bias_bandwidth"
    [turbulence]="src/piston/turbulence.rs src/piston/spectrum.rs|turbulence piston"
    [fft]="src/math/fft.rs|fft"
)
NEEDS_CLI=" seeding turbulence "
ORDER=(estimators statistics special spectrum noise interferogram dispersion finite_scan turbulence noise_simulation seeding fft)

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

for area in "${areas[@]}"; do
    spec=${AREAS[$area]:-}
    if [[ -z $spec ]]; then
        echo "unknown area '$area'; areas: ${ORDER[*]}" >&2
        exit 2
    fi
    files=() tests=()
    for f in ${spec%%|*}; do files+=(--file "$f"); done
    # --cargo-arg, not "-- --test": cargo-mutants passes arguments after
    # "--" to the test run only, and would build every test binary.
    for t in ${spec##*|}; do tests+=(--cargo-arg="--test=$t"); done
    [[ $NEEDS_CLI == *" $area "* ]] || tests+=(--cargo-arg=--no-default-features)
    echo "== $area: ${spec%%|*} with ${spec##*|}"
    mkdir -p "mutants.out/$area"
    cargo mutants "${files[@]}" "${tests[@]}" --output "mutants.out/$area" "$@" || true
done
