# Sourced by benches/plan_presets.sh and benches/plan_envelope.sh: builds
# the release binary and defines `run`, which times one `v2ref plan` with
# /usr/bin/time -v and prints one row of their tables.
#
#   LABEL_WIDTH=24; . benches/plan_run.sh    # from the repository root
cargo build --release --quiet
exe="${CARGO_TARGET_DIR:-target}/release/v2ref"
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (GNU time: apt-get install time)" >&2; exit 2; }
threads="${THREADS:-0}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run LABEL LIMIT_S ARGS... -> one row: wall time and peak memory of
# `v2ref plan ARGS`, and whether they are within LIMIT_S and 1 GB.
run() {
    local label=$1 limit=$2
    shift 2
    local log="$work/time.log" status=0
    /usr/bin/time -v "$exe" plan "$@" --threads "$threads" --quiet --json \
        >"$work/out.json" 2>"$log" || status=$?
    local wall rss_kb rss_mb verdict
    wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$log" |
        awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s }')
    rss_kb=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$log")
    rss_mb=$(awk "BEGIN { printf \"%.0f\", $rss_kb / 1024 }")
    verdict=$(awk "BEGIN { print ($wall <= $limit && $rss_kb <= 1048576) ? \"yes\" : \"NO\" }")
    [ "$status" -eq 0 ] || verdict="exit $status"
    printf "| %-${LABEL_WIDTH:-24}s | %8.1f | %7s | %6s s, 1 GB | %-9s |\n" "$label" "$wall" "$rss_mb" "$limit" "$verdict"
}
