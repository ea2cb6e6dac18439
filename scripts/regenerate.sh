#!/usr/bin/env bash
# Writes every file generated from the one declaration of the physical
# inputs (crates/v2ref-commands/src/parameters/table.rs, `Physical::DEFAULT`) and the CLI's flags:
# python/v2ref/_declaration.py, the physical keyword arguments of the
# signatures in python/v2ref/__init__.py, the input table of
# docs/conventions.md (all three by the binary's test
# `generated_files_are_the_declarations`), then the stub
# python/v2ref/__init__.pyi from the package's source (scripts/stub.py).
# Run it after changing a parameter, a flag or a docstring; the tests of
# both (cargo test, tests/python/test_parameters.py) fail until it is run.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
V2REF_REGENERATE=1 cargo test --release --bin v2ref generated_files_are_the_declarations
python3 scripts/stub.py
