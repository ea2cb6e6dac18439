#!/usr/bin/env bash
# Every test of v2ref's default tier, on a fresh machine: the Rust suite,
# then the Python suite (the `v2ref` package built from this checkout, and
# the independent NumPy pipeline scored by the release binary on the
# conformance vectors). The slow tier: tests/README.md ("Tiers"); .ci/run
# runs both.
# Creates .venv and installs what it needs (tests/python/requirements.txt:
# numpy, pytest, maturin, astropy, oifits) from the package registry;
# nothing installed by hand is assumed. Run from anywhere.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Each step's wall time is printed (`timing:` lines) so that the README's
# timings can be measured on a cold checkout.
#
# The Python environment (mostly the package registry and the disk) is made
# while cargo builds (the two cores); its log is printed if it fails.
env_log=$(mktemp)
build_log=$(mktemp)
py_log=$(mktemp)
trap 'rm -f "$env_log" "$build_log" "$py_log"; kill 0 2>/dev/null' INT TERM
trap 'rm -f "$env_log" "$build_log" "$py_log"' EXIT
t=$SECONDS
(
    if [ ! -x .venv/bin/python ]; then
        python3 -m venv .venv
    fi
    .venv/bin/pip install --quiet --upgrade pip
    .venv/bin/pip install --quiet -r tests/python/requirements.txt
) > "$env_log" 2>&1 &
environment=$!

# One build makes the library, the binary (target/release/v2ref, which the
# Python suite also runs) and the one test binary (tests/suite.rs): a
# separate `cargo build` would build it all again, as the tests'
# dependencies change the features of shared crates. The doc examples
# (each compiled as a program of its own: a minute of CPU) are the slow
# tier's, which `.ci/run` runs with `cargo test --release --doc`.
cargo test --release --lib --bins --tests --no-run
echo "timing: release build of the binary and the tests $((SECONDS - t)) s"
if ! wait "$environment"; then
    cat "$env_log" >&2
    echo "scripts/test.sh: the Python environment could not be made" >&2
    exit 1
fi
echo "timing: Python environment ready $((SECONDS - t)) s after the start (made during the build)"

# The Python side (the package built by maturin: the crate and 50-odd
# dependencies compiled again, with other features, and the bindings; then
# the Python tests) runs while the Rust tests run: cargo holds no lock on
# the target folder meanwhile, and the binary the Python tests call is
# built. Measured on a fresh clone: the Rust tests alone 71 s, the package
# alone 49 s, both at once 116 s, the Python tests 14 s after them. The
# Python output is printed after the Rust tests'; Ctrl-C stops both.
t=$SECONDS
(
    if ! .venv/bin/pip install --quiet --no-build-isolation . > "$build_log" 2>&1; then
        exit 100
    fi
    echo "timing: Python package built $((SECONDS - t)) s after the Rust tests started"
    V2REF_BIN="${CARGO_TARGET_DIR:-target}/release/v2ref" .venv/bin/python -m pytest -q tests/python
) > "$py_log" 2>&1 &
python_side=$!
rust=0
cargo test --release --lib --bins --tests || rust=$?
echo "timing: Rust tests run $((SECONDS - t)) s"
status=0
wait "$python_side" || status=$?
if [ "$status" -eq 100 ]; then
    cat "$build_log" >&2
    echo "scripts/test.sh: the Python package did not build" >&2
    exit 1
fi
cat "$py_log"
echo "timing: Python package built and tested $((SECONDS - t)) s after the Rust tests started"
echo "timing: scripts/test.sh in all $SECONDS s"
if [ "$status" -eq 5 ]; then
    echo "scripts/test.sh: pytest collected no tests in tests/python; there must be tests" >&2
    exit 1
fi
if [ "$rust" -ne 0 ]; then
    exit "$rust"
fi
exit "$status"
