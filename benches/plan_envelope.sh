#!/usr/bin/env bash
# The planner's cost at the corners of the envelope issue 44 states for it:
# visible to K, 0.1-10 m apertures, 10-400 m baselines, bright to faint.
# Each corner is a default `v2ref plan` (the 20 x 4 grid, target sigma(V^2)
# 1e-3) of a point source; two corners also with --verify. Reports each
# run's wall time and peak resident memory (/usr/bin/time -v) against the
# limits (plan 10 s, --verify 60 s, 1 GB, on 2 cores). A benchmark, not a
# test: it reports, it does not fail; run it on an otherwise idle machine.
#
#   benches/plan_envelope.sh              # all 16 corners, release build
#   THREADS=1 benches/plan_envelope.sh    # worker threads (default 0: all)
#
# Corners: V (0.55 um, 50 nm) or K (2.2 um, 400 nm); apertures 0.1 or 10 m;
# baselines 10 or 400 m; 1e4 (faint) or 1e8 (bright) photons/s at the
# detector; 0.8" seeing at 0.5 um, 10 m/s wind along the baseline, a 25 m
# outer scale.
set -euo pipefail
cd "$(dirname "$0")/.."
LABEL_WIDTH=34
. benches/plan_run.sh

echo "| corner                             |   wall s | peak MB | limits        | within    |"
echo "|------------------------------------|----------|---------|---------------|-----------|"
for band in "V 0.55 50" "K 2.2 400"; do
    read -r name wl bw <<<"$band"
    for aperture in 0.1 10; do
        for baseline in 10 400; do
            for rate in 1e4 1e8; do
                args=(--wavelength-um "$wl" --bandwidth-nm "$bw" --aperture-m "$aperture"
                    --baseline-m "$baseline" --photon-rate-per-s "$rate" --source point
                    --seeing-arcsec 0.8 --seeing-wavelength-um 0.5 --outer-scale-m 25)
                label="$name ${aperture} m, ${baseline} m, ${rate}/s"
                run "$label" 10 "${args[@]}"
                if [ "$aperture $baseline $rate" = "10 400 1e8" ]; then
                    run "$label --verify" 60 "${args[@]}" --verify
                fi
            done
        done
    done
done
echo
echo "$(nproc) cores, THREADS=$threads, $(date -u +%Y-%m-%dT%H:%MZ), load average $(cut -d' ' -f1-3 /proc/loadavg)"
