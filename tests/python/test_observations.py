"""The observation layout from Python (issue 44): `synthesize(layout=
"observation", observations=K, dead_time_s=T)` is `v2ref synth --layout
observation --observations K --dead-time-s T` bit for bit, its refusals name
the keyword, and `estimate(rows, sidecar=)` takes one observation's rows of
such a set, as the CLI's `estimate --sidecar SET.json --input ROWS` does.

Build and install first: `pip install .` (or `maturin develop --release`).
"""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import v2ref

BIN = os.environ.get("V2REF_BIN", str(Path(__file__).resolve().parents[2] / "target/release/v2ref"))

SET = dict(rows=120, samples=32, fringe_hz=250.0, layout="observation", observations=4,
           dead_time_s=0.01, reference_blocks=0, seed=3)


def test_observations_are_the_clis(tmp_path):
    rows, sidecar = v2ref.synthesize(**SET)
    stem = tmp_path / "obs"
    subprocess.run([BIN, "synth", "--out", str(stem), "--rows", "120", "--samples", "32",
                    "--fringe-hz", "250", "--layout", "observation", "--observations", "4",
                    "--dead-time-s", "0.01", "--reference-blocks", "0", "--seed", "3",
                    "--quiet"], check=True)
    assert np.array_equal(rows, np.load(f"{stem}.npy"))
    layout = sidecar["layout"]
    assert layout["sequences"] == 4 and layout["rows_per_sequence"] == [30] * 4
    assert layout["stride_samples"] > 32
    assert "not forced to zero" in layout["note"]


def test_one_observation_is_estimated_with_the_sets_sidecar():
    rows, sidecar = v2ref.synthesize(**SET)
    whole = v2ref.estimate(rows, sidecar=sidecar, bias="counts")
    second = v2ref.estimate(rows[30:60], sidecar=sidecar, bias="counts")
    assert np.array_equal(second["v1_sq"], whole["v1_sq"][30:60])


@pytest.mark.parametrize("kwargs, message", [
    (dict(observations=7), "observations: 7: must divide the rows"),
    (dict(observations=0), "observations"),
    (dict(dead_time_s=-1.0), "dead_time_s"),
    (dict(layout="sequences"), "observations: 4: only with layout observation"),
])
def test_observation_keywords_are_checked(kwargs, message):
    with pytest.raises(ValueError, match=message):
        v2ref.synthesize(**dict(SET, **kwargs))
