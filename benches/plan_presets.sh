#!/usr/bin/env bash
# The planner's cost on every instrument preset (`v2ref plan --instrument
# NAME`, docs/instruments.md), and with --verify on two of them: wall time
# and peak resident memory of each run (/usr/bin/time -v), against the
# limits issue 44 sets (plan 10 s, --verify 60 s, 1 GB, on 2 cores). A
# benchmark, not a test: it reports, it does not fail; run it on an
# otherwise idle machine (its numbers are the machine's).
#
#   benches/plan_presets.sh                 # every preset, release build
#   benches/plan_presets.sh npoi mroi       # some
#   THREADS=1 benches/plan_presets.sh       # worker threads (default 0: all)
#
# Each preset observes a star its instrument would: a uniform disk of the
# diameter below, of the magnitude below in the band below, through 0.8"
# seeing at 0.5 um, 10 m/s wind and a 25 m outer scale, to sigma(V^2) 1e-3.
set -euo pipefail
cd "$(dirname "$0")/.."
LABEL_WIDTH=24
. benches/plan_run.sh

# name  magnitude band  diameter_mas  verify?
cases=(
    "chara-mirc-x    4 h  0.5 verify"
    "chara-fluor     3 ks 1.0 -"
    "vlti-pionier    5 h  1.0 verify"
    "vlti-gravity-ft 7 ks 0.5 -"
    "npoi            2 r  2.0 -"
    "mroi            6 h  0.5 -"
)
wanted=("$@")

echo "| plan                     |   wall s | peak MB | limits        | within    |"
echo "|--------------------------|----------|---------|---------------|-----------|"
for c in "${cases[@]}"; do
    read -r name mag band diam verify <<<"$c"
    if [ ${#wanted[@]} -gt 0 ] && [[ ! " ${wanted[*]} " == *" $name "* ]]; then
        continue
    fi
    args=(--instrument "$name" --source ud --diameter-mas "$diam"
        --magnitude "$mag" --magnitude-band "$band"
        --seeing-arcsec 0.8 --seeing-wavelength-um 0.5 --outer-scale-m 25
        --target-sigma-v2 1e-3)
    run "$name" 10 "${args[@]}"
    if [ "$verify" = verify ]; then
        run "$name --verify" 60 "${args[@]}" --verify
    fi
done
echo
echo "$(nproc) cores, THREADS=$threads, $(date -u +%Y-%m-%dT%H:%MZ), load average $(cut -d' ' -f1-3 /proc/loadavg)"
