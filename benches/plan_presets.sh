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
cargo build --release --quiet
exe="${CARGO_TARGET_DIR:-target}/release/v2ref"
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (GNU time: apt-get install time)" >&2; exit 2; }
threads="${THREADS:-0}"

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
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run LABEL LIMIT_S ARGS... -> one row of the table
run() {
    local label=$1 limit=$2
    shift 2
    local log="$work/time.log"
    local status=0
    /usr/bin/time -v "$exe" plan "$@" --threads "$threads" --quiet --json \
        >"$work/out.json" 2>"$log" || status=$?
    local wall rss_kb
    wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$log" |
        awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s }')
    rss_kb=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$log")
    local rss_mb verdict
    rss_mb=$(awk "BEGIN { printf \"%.0f\", $rss_kb / 1024 }")
    verdict=$(awk "BEGIN { print ($wall <= $limit && $rss_kb <= 1048576) ? \"yes\" : \"NO\" }")
    [ "$status" -eq 0 ] || verdict="exit $status"
    printf '| %-24s | %8.1f | %7s | %6s s, 1 GB | %-9s |\n' "$label" "$wall" "$rss_mb" "$limit" "$verdict"
}

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
