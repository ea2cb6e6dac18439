"""The Python suite's two tiers, as the Rust suite's: tests marked
``@pytest.mark.slow`` are skipped unless ``V2REF_SLOW=1``; ``.ci/run``
always runs them (``V2REF_SLOW=1 pytest -m slow tests/python``) after the
README's test command."""

import os

import pytest


def pytest_configure(config):
    config.addinivalue_line("markers", "slow: the slow tier (V2REF_SLOW=1 runs it; .ci/run does)")


def pytest_collection_modifyitems(config, items):
    if os.environ.get("V2REF_SLOW") == "1":
        return
    skip = pytest.mark.skip(reason="slow tier: V2REF_SLOW=1 runs it (.ci/run does)")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)
