#!/usr/bin/env bash
# The oracle library's public API, listed from rustdoc's JSON
# (scripts/public_api.py), against the committed listing in
# crates/v2ref/public-api/: fails with the diff when the surface changed and
# its listing was not updated with it.
#
#   scripts/public_api.sh            # check (CI: .ci/run)
#   scripts/public_api.sh --update   # rewrite the listings, then review `git diff crates/v2ref/public-api`
#
# rustdoc's JSON output is unstable: a nightly toolchain is needed
# (rustup toolchain install nightly).
set -euo pipefail
cd "$(dirname "$0")/.."

update=0
[ "${1:-}" = --update ] && update=1
out="${CARGO_TARGET_DIR:-target}/public-api"
status=0
# The facade and the crate it re-exports from, whose items the listing
# follows (scripts/public_api.py).
for package in v2ref v2ref-core; do
  cargo +nightly rustdoc --quiet -p "$package" --lib --target-dir "$out" \
    -- -Z unstable-options --output-format json
done
listing=$(python3 scripts/public_api.py "$out/doc/v2ref.json" "$out/doc/v2ref_core.json")
counts=$(python3 scripts/public_api.py --counts "$out/doc/v2ref.json" "$out/doc/v2ref_core.json")
if [ "$update" = 1 ]; then
  printf '%s\n' "$listing" > crates/v2ref/public-api/default.txt
  echo "crates/v2ref/public-api/default.txt: $counts"
elif ! diff -u crates/v2ref/public-api/default.txt <(printf '%s\n' "$listing"); then
  echo "the public API of the crate v2ref is not crates/v2ref/public-api/default.txt:"
  echo "review the change, then run scripts/public_api.sh --update and commit the listing"
  status=1
fi
# The stable surface stays small: at most 250 items (types, functions,
# constants, each once, whatever its paths).
items=${counts##*module items }
if [ "$items" -gt 250 ]; then
  echo "the crate v2ref has $items public items; at most 250"
  status=1
fi
exit "$status"
