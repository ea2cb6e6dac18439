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
# listing name, then the library's features for it
while read -r name features; do
  # shellcheck disable=SC2086
  cargo +nightly rustdoc --quiet -p v2ref --lib --target-dir "$out" $features \
    -- -Z unstable-options --output-format json
  listing=$(python3 scripts/public_api.py "$out/doc/v2ref.json")
  if [ "$update" = 1 ]; then
    printf '%s\n' "$listing" > "crates/v2ref/public-api/$name.txt"
    echo "crates/v2ref/public-api/$name.txt: $(python3 scripts/public_api.py --counts "$out/doc/v2ref.json")"
  elif ! diff -u "crates/v2ref/public-api/$name.txt" <(printf '%s\n' "$listing"); then
    echo "the public API of the library (${features:-default features}) is not crates/v2ref/public-api/$name.txt:"
    echo "review the change, then run scripts/public_api.sh --update and commit the listing"
    status=1
  fi
done <<'LISTINGS'
default
LISTINGS
exit "$status"
