#!/usr/bin/env bash
# Instruction counts of each hot path and of its floor (benches/floors.rs),
# one thread, under valgrind's callgrind: a measure that does not depend on
# what else the machine runs. Each side is counted as (setup + one run)
# minus (setup alone), so the data's preparation is left out.
#
#   benches/floors_callgrind.sh                 # every path
#   benches/floors_callgrind.sh estimate        # some
set -euo pipefail
cd "$(dirname "$0")/.."
cargo bench --bench floors --no-run --quiet 2>/dev/null || cargo bench --bench floors --no-run
target="${CARGO_TARGET_DIR:-target}"
exe=$(ls -t "$target"/release/deps/floors-* | grep -v '\.d$' | head -1)
paths=("$@")
if [ ${#paths[@]} -eq 0 ]; then
    read -r -a paths <<< "$("$exe" --list)"
fi
count() { # path side repeats -> instructions
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$exe" "$1" \
        --threads 1 --only "$2" --repeats "$3" 2>&1 >/dev/null |
        sed -n 's/.*Collected : *\([0-9]*\).*/\1/p'
}
printf '%-20s %16s %16s %7s\n' path "floor instr" "v2ref instr" ratio
for p in "${paths[@]}"; do
    setup=$(count "$p" floor 0)
    floor=$(( $(count "$p" floor 1) - setup ))
    ours=$(( $(count "$p" v2ref 1) - setup ))
    printf '%-20s %16d %16d %7.2f\n' "$p" "$floor" "$ours" "$(awk "BEGIN { print $ours / $floor }")"
done
