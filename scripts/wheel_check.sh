#!/usr/bin/env bash
# What a Python user without Rust installs, checked (run by .ci/run after
# scripts/test.sh, whose .venv holds maturin and whose build left the
# bindings compiled in target/):
# 1. the abi3 wheel, built by maturin, installed into a fresh virtual
#    environment on a PATH with no cargo and no rustc, imported, and the
#    Python suite run against it (the CLI tests call the release binary,
#    V2REF_BIN, as scripts/test.sh gives it);
# 2. the sdist, unpacked in a scratch folder and built into a wheel there,
#    from its own files alone.
# Both builds share the workspace's target folder: the registry's crates are
# not compiled again (the sdist's own crates are, from their new place).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$PWD
target="${CARGO_TARGET_DIR:-$root/target}"
case $target in /*) ;; *) target="$root/$target" ;; esac
maturin="$root/.venv/bin/maturin"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# Runs a command with its output kept, printed only if it fails.
quiet() {
  if ! "$@" > "$scratch/log" 2>&1; then
    cat "$scratch/log" >&2
    return 1
  fi
}

t=$SECONDS
quiet env CARGO_TARGET_DIR="$target" "$maturin" build --release --locked --out "$scratch/wheel"
wheel=$(ls "$scratch"/wheel/v2ref-*-abi3-*.whl)
echo "timing: abi3 wheel built $((SECONDS - t)) s ($(basename "$wheel"))"

# The PATH of a machine without Rust: every folder holding cargo or rustc left out.
no_rust_path=$(python3 -c 'import os
print(":".join(d for d in os.environ["PATH"].split(os.pathsep)
               if d and not any(os.access(os.path.join(d, x), os.X_OK) for x in ("cargo", "rustc"))))')
venv="$scratch/venv"
python3 -m venv "$venv"
t=$SECONDS
env PATH="$venv/bin:$no_rust_path" bash -c '
  if command -v cargo || command -v rustc; then
    echo "wheel check: a Rust toolchain is still on the PATH (above)"; exit 1
  fi
  pip install --quiet "$1"
  python -c "import v2ref, sys; sys.exit(0 if \"site-packages\" in v2ref.__file__ else 1)"' _ "$wheel"
echo "timing: wheel installed and imported in a fresh venv, no Rust on PATH $((SECONDS - t)) s"

t=$SECONDS
"$venv/bin/pip" install --quiet -r tests/python/requirements.txt
echo "timing: the Python tests' requirements in the fresh venv $((SECONDS - t)) s"
t=$SECONDS
env PATH="$venv/bin:$no_rust_path" V2REF_BIN="$target/release/v2ref" \
  python -m pytest -q -p no:cacheprovider tests/python
echo "timing: the Python tests against the installed wheel $((SECONDS - t)) s"

# The sdist alone: unpacked away from the checkout, built with its own files
# (not --locked: maturin's sdist drops the command line from the workspace,
# and cargo prunes its dependencies from the lock; no version changes).
t=$SECONDS
quiet "$maturin" sdist --out "$scratch/sdist"
mkdir "$scratch/unpacked"
tar -xzf "$scratch"/sdist/v2ref-*.tar.gz -C "$scratch/unpacked"
(cd "$scratch"/unpacked/v2ref-* &&
  quiet env CARGO_TARGET_DIR="$target" "$maturin" build --release --out "$scratch/from_sdist")
ls "$scratch"/from_sdist/v2ref-*-abi3-*.whl > /dev/null
echo "timing: sdist made, unpacked and built into a wheel $((SECONDS - t)) s"
