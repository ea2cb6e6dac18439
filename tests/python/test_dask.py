"""The Monte Carlo on a Dask cluster (``v2ref.dask``): a LocalCluster of 2
worker processes gives the one process's bits, with a worker killed
mid-run, and a run resumed from a checkpoint folder computes only the
ranges it lacks. Skipped when dask.distributed is not installed."""

import os
import subprocess
import sys

import pytest

distributed = pytest.importorskip("distributed")

import v2ref  # noqa: E402
from v2ref import dask as v2dask  # noqa: E402

#: Small runs: 6 units of 8192 rows of 32 samples (a unit each per task).
SMALL = dict(trials=6 * 8192 - 100, samples=32, seed=5, threads=1)


def bits(x):
    """``x`` with every float as its exact hex form (so == compares bits)."""
    if isinstance(x, float):
        return x.hex()
    if isinstance(x, dict):
        return {k: bits(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [bits(v) for v in x]
    return x


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.mark.parametrize(
    "case",
    [
        {},  # the noise-only fast path
        # Every row estimated, with piston (costlier: 3 units).
        {"bias": "counts", "fringe_hz": 300.0, "trials": 3 * 8192 - 7},
    ],
    ids=["fast", "piston-rows"],
)
def test_simulate_on_two_workers_gives_the_one_process_bits(client, case):
    kw = {**SMALL, **case}
    one = v2ref.simulate(**kw)
    on_cluster = v2ref.simulate(**kw, client=client, chunk_units=1)
    assert bits(on_cluster) == bits(one)
    # Another split (uneven ranges) changes no bit either.
    assert bits(v2ref.simulate(**kw, client=client, chunk_units=2)) == bits(one)


def test_piston_on_two_workers_gives_the_one_process_bits(client, tmp_path):
    kw = dict(fringe_hz=[300.0, 700.0, 1000.0], scans=20, samples=32, seed=3, threads=1)
    one = v2ref.piston(**kw)
    assert bits(v2ref.piston(**kw, client=client)) == bits(one)
    # Resumed from a checkpoint lacking one frequency: the same bits.
    v2ref.piston(**kw, checkpoint=tmp_path / "ck")
    files = sorted((tmp_path / "ck").iterdir())
    assert len(files) == 3
    files[1].unlink()
    assert bits(v2ref.piston(**kw, client=client, checkpoint=tmp_path / "ck")) == bits(one)
    assert len(list((tmp_path / "ck").iterdir())) == 3


def test_a_worker_killed_mid_run_changes_no_bit(client, tmp_path):
    marker = tmp_path / "killed"

    class KillOnce(distributed.WorkerPlugin):
        """Ends its worker's process when a v2ref task starts, once."""

        def transition(self, key, start, finish, **kwargs):
            name = key if isinstance(key, str) else str(key)
            if finish == "executing" and name.startswith("v2ref-"):
                try:  # created new: one worker only, even two starting at once
                    os.close(os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY))
                except FileExistsError:
                    return
                os._exit(1)

    one = v2ref.simulate(**SMALL)
    client.register_plugin(KillOnce(), name="v2ref-kill-once")
    try:
        # seed 6: keys not yet in the cluster's memory from another test.
        on_cluster = v2ref.simulate(**{**SMALL, "seed": 6}, client=client, chunk_units=1)
    finally:
        client.unregister_worker_plugin("v2ref-kill-once")
    assert marker.exists(), "no worker was killed"
    assert bits(on_cluster) == bits(v2ref.simulate(**{**SMALL, "seed": 6}))
    assert bits(one) != bits(on_cluster)  # the seeds differ: the check has power


def args_of(**kw):
    """The arguments ``v2ref.simulate`` hands ``v2ref.dask`` for ``kw``."""
    seen = {}

    def capture(command, args, client, checkpoint, chunk_units):
        seen["args"] = args
        return (None, 0)

    real = v2dask._run_units
    v2dask._run_units = capture
    try:
        v2ref.simulate(**kw, checkpoint="unused-never-created")
    finally:
        v2dask._run_units = real
    return seen["args"]


def test_a_resumed_run_computes_only_the_missing_ranges(client, tmp_path):
    folder = tmp_path / "ck"
    args = args_of(**SMALL)
    whole, computed = v2dask._run_units("simulate", args, client, folder, 1)
    assert computed == 6
    files = sorted(folder.iterdir())
    assert len(files) == 6 and all(f.name.endswith(".partial") for f in files)
    # An interrupted run: two ranges never written, a temporary left behind.
    kept = {f.name: f.stat().st_ino for f in files[:4]}
    for f in files[4:]:
        f.unlink()
    (folder / ".v2ref-tmp-1-1-half-written").write_bytes(b"v2r")
    again, computed = v2dask._run_units("simulate", args, client, folder, 1)
    assert computed == 2
    assert bits(again) == bits(whole) == bits(v2ref.simulate(**SMALL))
    assert {f.name: f.stat().st_ino for f in folder.iterdir() if f.name in kept} == kept
    # Complete: nothing computed, even on no cluster.
    assert v2dask._run_units("simulate", args, None, folder, 1)[1] == 0


def test_a_checkpoint_link_or_foreign_file_is_refused_never_followed(tmp_path):
    folder = tmp_path / "ck"
    args = args_of(**SMALL)
    v2dask._run_units("simulate", args, None, folder, 3)
    first = sorted(folder.iterdir())[0]
    # A link at a partial's name (to that very partial, moved away): refused.
    moved = tmp_path / "elsewhere"
    first.rename(moved)
    first.symlink_to(moved)
    with pytest.raises(ValueError, match="checkpoint: .* link is never followed"):
        v2dask._run_units("simulate", args, None, folder, 3)
    first.unlink()
    # A partial grown by one byte: refused before it is read.
    moved.rename(first)
    with open(first, "ab") as f:
        f.write(b"\0")
    with pytest.raises(ValueError, match="checkpoint: .* bytes, not the"):
        v2dask._run_units("simulate", args, None, folder, 3)
    first.unlink()
    # Another request's partial under this request's name: refused.
    other = args_of(**{**SMALL, "seed": 99})
    foreign = v2dask._run_units("simulate", other, None, tmp_path / "other", 3)
    assert foreign[1] == 2
    src = sorted((tmp_path / "other").iterdir())[0]
    first.write_bytes(src.read_bytes())
    before = sorted(p.name for p in folder.iterdir())
    with pytest.raises(ValueError, match="partial: computed for another request"):
        v2dask._run_units("simulate", args, None, folder, 3)
    assert sorted(p.name for p in folder.iterdir()) == before  # the reader wrote nothing


def test_import_v2ref_does_not_import_dask():
    code = "import sys, v2ref; v2ref.simulate(trials=8, samples=16); print('dask' in sys.modules or 'distributed' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_bad_units_arguments_are_value_errors(tmp_path):
    with pytest.raises(ValueError, match="chunk_units"):
        v2ref.simulate(**SMALL, checkpoint=tmp_path / "ck", chunk_units=0)
    assert not (tmp_path / "ck").exists()
    with pytest.raises(ValueError, match="command"):
        v2ref._v2ref._units_count("bias", ())


#: A short plan of bright H-band targets (as tests/python/test_plan_targets.py).
TARGETS_SHARED = dict(
    wavelength_um=1.65, bandwidth_nm=300.0, fringe_hz=[500.0], stroke_um=[32.0],
    scans=50, aperture_m=1.8, target_sigma_v2=1e-2, seed=7, throughput=0.01, threads=1,
)
TARGET_ROWS = [
    {"name": "alpha", "magnitude": 5.0, "band": "H", "diameter_mas": 1.0, "ra_deg": 10.5, "dec_deg": -20.0},
    {"name": "beta", "magnitude": "5x", "band": "H"},
    {"name": "gamma", "magnitude": 6.0, "band": "h", "diameter_mas": None},
]


def test_plan_targets_on_two_workers_gives_the_one_process_table(client, tmp_path):
    one = v2ref.plan_targets(TARGET_ROWS, **TARGETS_SHARED)
    assert [r["status"] for r in one] == ["ok", "error", "ok"]
    on_cluster = v2ref.plan_targets(TARGET_ROWS, **TARGETS_SHARED, client=client)
    assert bits(on_cluster) == bits(one)  # every field of every row, in order
    # A file is read by the caller (its lines kept): the same table.
    path = tmp_path / "list.csv"
    path.write_text("# a comment\nname,magnitude,band\nalpha,5,H\r\n\ngamma,6,h\n")
    from_file = v2ref.plan_targets(path, **TARGETS_SHARED)
    assert bits(v2ref.plan_targets(path, **TARGETS_SHARED, client=client)) == bits(from_file)
    assert [r["line"] for r in from_file] == [3, 5]
    # Power: another shared seed changes the planned rows' numbers.
    other = v2ref.plan_targets(TARGET_ROWS, **{**TARGETS_SHARED, "seed": 8}, client=client)
    assert bits(other) != bits(one)


def test_synthesize_truth_on_two_workers_gives_the_one_process_set(client, monkeypatch):
    # 2 blocks' worth of rows: 8 reference blocks of 2 units (the truth's
    # reference run, run as 4-unit ranges here), rows made in the caller.
    kw = dict(rows=8192 + 100, samples=32, seed=4, threads=1)
    data, sidecar = v2ref.synthesize(**kw)
    real = v2dask._partials
    monkeypatch.setattr(v2dask, "_partials", lambda *a: real(*a, chunk_units=4))
    on_cluster = v2ref.synthesize(**kw, client=client)
    assert on_cluster[0].tobytes() == data.tobytes()
    assert bits(on_cluster[1]) == bits(sidecar)  # the truth, every field
    other = v2ref.synthesize(**{**kw, "seed": 5}, client=client)
    assert bits(other[1]["truth"]) != bits(sidecar["truth"])  # power


#: A plan whose verification (320 observations of 145 scans, sequences
#: of 2900 scans 378 samples apart: batches of 15 and 1 sequences) runs
#: as 2 units.
PLAN_VERIFIED = dict(
    wavelength_um=2.2, bandwidth_nm=400.0, source="point", baseline_m=50.0,
    photon_rate_per_s=2e6, read_noise=2.0, fringe_hz=[800.0], stroke_um=[32.0],
    scans=400, target_sigma_v2=3e-3, dead_time_s=0.1, threads=1,
    verify=True, verify_observations=320,
)


def test_plan_verify_on_two_workers_gives_the_one_process_bits(client, tmp_path):
    one = v2ref.plan(**PLAN_VERIFIED)
    assert one["verification"]["observations"] == 320
    assert bits(v2ref.plan(**PLAN_VERIFIED, client=client)) == bits(one)
    # Resumed from a checkpoint lacking one of its 2 batches: the same bits,
    # the batch kept not rewritten.
    folder = tmp_path / "ck"
    assert bits(v2ref.plan(**PLAN_VERIFIED, checkpoint=folder)) == bits(one)
    files = sorted(folder.iterdir())
    assert [f.name.split("-")[1] for f in files] == ["verify", "verify"]
    kept = files[0].stat().st_ino
    files[1].unlink()
    assert bits(v2ref.plan(**PLAN_VERIFIED, client=client, checkpoint=folder)) == bits(one)
    assert sorted(folder.iterdir()) == files and files[0].stat().st_ino == kept
    # Power: the verification's seed (the plan's) changes its numbers.
    other = v2ref.plan(**{**PLAN_VERIFIED, "seed": 2, "verify_observations": 64}, client=client)
    assert bits(other["verification"]["achieved_sigma"]) != bits(one["verification"]["achieved_sigma"])


def test_powered_set_on_two_workers_gives_the_one_process_set(client, tmp_path):
    # The smallest powered set (0.7 s here): 268 288 rows of 25 samples,
    # its truth's reference run 264 units (five tasks of up to 64 here).
    data, sidecar = v2ref.powered_set("short_scan_odd")
    assert data.shape == (268288, 25) and sidecar["data"]["npy"] == "short_scan_odd.npy"
    on_cluster = v2ref.powered_set("short_scan_odd", client=client)
    assert on_cluster[0].tobytes() == data.tobytes()
    assert bits(on_cluster[1]) == bits(sidecar)  # the truth, every field
    # Resumed from a checkpoint lacking two of its ranges: the same set.
    folder = tmp_path / "ck"
    resumed = v2ref.powered_set("short_scan_odd", checkpoint=folder)
    assert bits(resumed[1]) == bits(sidecar)
    # 4 ranges of 66 units (no client), in unit order.
    files = sorted(folder.iterdir(), key=lambda f: int(f.name.split("-")[3]))
    assert len(files) == 4 and all(f.name.startswith("v2ref-powered-") for f in files)
    kept = {f.name: f.stat().st_ino for f in files[::2]}
    files[1].unlink()
    files[3].unlink()
    again = v2ref.powered_set("short_scan_odd", client=client, checkpoint=folder)
    assert again[0].tobytes() == data.tobytes() and bits(again[1]) == bits(sidecar)
    # Each gap of 66 recomputed as ranges of 64 and 2 on the 2 workers,
    # the rest kept as they were.
    assert {f.name: f.stat().st_ino for f in folder.iterdir() if f.name in kept} == kept
    assert len(list(folder.iterdir())) == 2 + 4


def test_powered_set_refuses_a_vector_with_piston_or_no_vector(tmp_path):
    with pytest.raises(ValueError, match=r"name: \"piston_low\" has piston.*accepted: noise_gaussian, "):
        v2ref.powered_set("piston_low", client=None, checkpoint=tmp_path / "ck")
    with pytest.raises(ValueError, match=r"name: no piston-free vector \"nope\"; accepted: .*integrating"):
        v2ref.powered_set("nope")
    with pytest.raises(TypeError, match="name"):
        v2ref.powered_set(3)
    assert not (tmp_path / "ck").exists()


def test_plan_targets_progress_on_two_workers(client):
    seen = []
    rows = v2ref.plan_targets(TARGET_ROWS, **TARGETS_SHARED, client=client, progress=lambda d, t: seen.append((d, t)))
    assert seen == [(1, 3), (2, 3), (3, 3)]
    assert bits(rows) == bits(v2ref.plan_targets(TARGET_ROWS, **TARGETS_SHARED))
