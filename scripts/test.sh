#!/usr/bin/env bash
# Every test of v2ref: the Rust suite, then the independent NumPy pipeline
# scored by the release binary on the conformance vectors (tests/python).
# Run from anywhere.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/pip install --quiet -r tests/python/requirements.txt

cargo test --release
cargo build --release

status=0
V2REF_BIN=target/release/v2ref .venv/bin/python -m pytest -q tests/python || status=$?
if [ "$status" -eq 5 ]; then
    echo "scripts/test.sh: pytest collected no tests in tests/python; there must be tests" >&2
    exit 1
fi
exit "$status"
