#!/usr/bin/env bash
# Instruction counts of the spectral channels' paths (benches/channels.rs),
# one thread, under valgrind's callgrind, setup subtracted (each side is
# counted as setup + one run, minus setup alone):
#
#   simulate-C-{none,piston}: simulate_channels of C channels, 4096 rows
#     each, against C times the one-channel (whole band) run (ratio) and
#     C times the run of one channel of the C alone (ratio'); limit 1.
#   estimate-C-{band,positive}: RowEstimator::estimate on each channel's
#     2048 rows against the real-FFT floor on the same rows; limit 1.5.
#
#   benches/channels_callgrind.sh                   # every case
#   benches/channels_callgrind.sh simulate-1-none simulate-6-none
#
# A simulate case's ratio needs its one-channel case (simulate-1-…)
# counted in the same call; the script adds it when it is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo bench --bench channels --no-run --quiet 2>/dev/null || cargo bench --bench channels --no-run
target="${CARGO_TARGET_DIR:-target}"
exe=${CHANNELS_EXE:-$(ls -t "$target"/release/deps/channels-* | grep -v '\.d$' | head -1)}
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
    read -r -a cases <<< "$("$exe" --list)"
fi
for c in "${cases[@]}"; do # the one-channel runs first
    case "$c" in simulate-*-*) one="simulate-1-${c##*-}"
        [[ " ${cases[*]} " == *" $one "* ]] || cases=("$one" "${cases[@]}") ;;
    esac
done
count() { # case side -> instructions
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$exe" --count "$1" "$2" 2>&1 >/dev/null |
        sed -n 's/.*Collected : *\([0-9]*\).*/\1/p'
}
declare -A one_channel
printf '%-20s %3s %14s %14s %14s %6s %6s %5s\n' case C "reference" "C x 1 of C" "v2ref" ratio "ratio'" limit
for c in "${cases[@]}"; do
    channels=$(echo "$c" | cut -d- -f2)
    setup=$(count "$c" setup)
    ours=$(( $(count "$c" run) - setup ))
    case "$c" in
    simulate-*)
        [ "$channels" = 1 ] && one_channel[${c##*-}]=$ours
        reference=$(( channels * one_channel[${c##*-}] ))
        split=$(( channels * ($(count "$c" one) - setup) ))
        limit=1.00 ;;
    estimate-*)
        reference=$(( $(count "$c" floor) - setup ))
        split=0
        limit=1.50 ;;
    esac
    printf '%-20s %3s %14d %14d %14d %6.3f %6s %5s\n' "$c" "$channels" "$reference" "$split" "$ours" \
        "$(awk "BEGIN { print $ours / $reference }")" \
        "$(awk "BEGIN { if ($split > 0) printf \"%.3f\", $ours / $split; else print \"-\" }")" "$limit"
done
