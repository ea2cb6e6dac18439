#!/usr/bin/env bash
# Every test of v2ref, on a fresh machine: the Rust suite, then the Python
# suite (the `v2ref` package built from this checkout, and the independent
# NumPy pipeline scored by the release binary on the conformance vectors).
# Creates .venv and installs what it needs (numpy, pytest, maturin) from the
# package registry; nothing installed by hand is assumed. Run from anywhere.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
fi
.venv/bin/pip install --quiet --upgrade pip
.venv/bin/pip install --quiet -r tests/python/requirements.txt

# Each step's wall time is printed (`timing:` lines) so that the README's
# timings can be measured on a cold checkout. One build makes the library,
# the binary (target/release/v2ref, which the Python suite also runs) and
# the one test binary (tests/suite.rs): a separate `cargo build` would build
# it all again, as the tests' dependencies change the features of shared
# crates.
t=$SECONDS; cargo test --release --no-run
echo "timing: release build of the binary and the tests $((SECONDS - t)) s"
t=$SECONDS; cargo test --release
echo "timing: Rust tests run $((SECONDS - t)) s"

# The package, built by maturin from this checkout into the venv.
t=$SECONDS
.venv/bin/pip install --quiet --no-build-isolation .

status=0
V2REF_BIN="${CARGO_TARGET_DIR:-target}/release/v2ref" .venv/bin/python -m pytest -q tests/python || status=$?
echo "timing: Python package build and tests $((SECONDS - t)) s"
if [ "$status" -eq 5 ]; then
    echo "scripts/test.sh: pytest collected no tests in tests/python; there must be tests" >&2
    exit 1
fi
exit "$status"
