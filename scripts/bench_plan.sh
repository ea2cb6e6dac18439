#!/usr/bin/env bash
# Wall time of the planner against its stated limit (20 s on 2 cores): the
# default plan and the CHARA-like plan of issue 26, three runs each, release
# build; prints the median and its ratio to the limit. Run from anywhere.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
cargo build --release --quiet
bin="${CARGO_TARGET_DIR:-target}/release/v2ref"
limit_s=20
chara=(--wavelength-um 1.65 --bandwidth-nm 300 --diameter-mas 0.5 --baseline-m 330
       --aperture-m 1 --wind-mps 10 --seeing-arcsec 1 --seeing-wavelength-um 0.5
       --magnitude 6 --magnitude-band h --throughput 0.05 --read-noise 1
       --target-sigma-v2 1e-4)
run() {
    local name=$1; shift
    local times=()
    for _ in 1 2 3; do
        local t0 t1
        t0=$(date +%s.%N)
        "$bin" plan "$@" --json > /dev/null 2>&1
        t1=$(date +%s.%N)
        times+=("$(echo "$t1 - $t0" | bc)")
    done
    local median
    median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n 2p)
    printf '%-10s median %6.1f s  (%.2f of the %d s limit)\n' "$name" "$median" \
        "$(echo "$median / $limit_s" | bc -l)" "$limit_s"
}
run default
run chara "${chara[@]}"
