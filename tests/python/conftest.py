"""The Python suite's two tiers, as the Rust suite's: tests marked
``@pytest.mark.slow`` are skipped unless ``V2REF_SLOW=1``; ``.ci/run``
always runs them (``V2REF_SLOW=1 pytest -m slow tests/python``) after the
README's test command.

One policy for the tests that run the release binary (marked
``@pytest.mark.needs_bin``; the binary is ``$V2REF_BIN``, default
``target/release/v2ref``, relative to the repository): when it is missing,
CI (``CI=true`` or ``V2REF_REQUIRE_BIN=1``) fails them, and a local run
skips them, saying why and how to build it."""

import os
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def release_binary() -> Path:
    """The v2ref binary the CLI tests run."""
    b = Path(os.environ.get("V2REF_BIN", ROOT / "target" / "release" / "v2ref"))
    return b if b.is_absolute() else ROOT / b


def binary_required() -> bool:
    """Whether a missing binary fails the tests (CI) rather than skipping them."""
    ci = os.environ.get("CI", "").lower() in ("1", "true", "yes")
    return ci or os.environ.get("V2REF_REQUIRE_BIN") == "1"


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: the slow tier (V2REF_SLOW=1 runs it; .ci/run does)")
    config.addinivalue_line(
        "markers", "needs_bin: runs the release binary (missing: CI fails, a local run skips)"
    )


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    if item.get_closest_marker("needs_bin") is None:
        return
    b = release_binary()
    if b.is_file():
        return
    why = f"no v2ref binary at {b} (cargo build --release, or set V2REF_BIN)"
    if binary_required():
        pytest.fail(f"{why}; CI=true or V2REF_REQUIRE_BIN=1 requires it", pytrace=False)
    pytest.skip(f"{why}; skipped locally, CI=true or V2REF_REQUIRE_BIN=1 fails instead")


def pytest_collection_modifyitems(config, items):
    if os.environ.get("V2REF_SLOW") == "1":
        return
    skip = pytest.mark.skip(reason="slow tier: V2REF_SLOW=1 runs it (.ci/run does)")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
