"""The Monte Carlo of v2ref on a Dask cluster (``pip install v2ref[dask]``).

The library splits a command into fixed work units (one generator each,
keyed by what it computes); here ranges of units run as Dask tasks, and
their partial results are reduced in unit order in the calling process,
so the answer is bit for bit the one-process answer whatever the number
of workers, the range size, a worker lost (its tasks run again) or a run
resumed from a checkpoint folder. The functions of :mod:`v2ref` call this
module when given ``client=`` or ``checkpoint=``; ``import v2ref`` does
not import Dask.

A checkpoint folder holds one file per finished range, named by the
request's key and the range (``v2ref-simulate-KEY-START-END.partial``),
written as a temporary ``.v2ref-tmp-…`` (created new, never through a
link), synced and linked into place (never over an existing entry). A
rerun with the same arguments reads the files of its key (regular files
of this user only, opened without following links, their checksum,
embedded key and range checked; nothing written while reading) and
computes only the missing units (:mod:`v2ref._checkpoint`).
"""

import hashlib as _hashlib
import json as _json
import math as _math
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import _v2ref
from ._checkpoint import Checkpoint as _Checkpoint
from ._checkpoint import checked_path as _checked_path
from ._checkpoint import checkpoint_path as _checkpoint_path
from ._checkpoint import record_bytes as _record_bytes

#: Fewest units of ``simulate`` per task: a task then computes for over
#: 20 times its overhead (benches/dask_units.py, on 2 shared cores: a unit
#: of the default simulate ~12.5 ms on one thread, a range's round trip
#: and setup ~27 ms, so 43 units or more keep the overhead under 5 %).
#: ``piston``'s units (one fringe frequency each) run one per task.
MIN_UNITS_PER_TASK = 64

#: Tasks per worker thread a run is split into when not told (enough to
#: balance the load and lose little to a worker lost, few enough to keep
#: the overhead small).
TASKS_PER_THREAD = 4

#: Times a task is retried after it failed (a worker lost mid-task is
#: handled by the scheduler itself: its tasks run again elsewhere).
RETRIES = 3

def _check_client(client: Any) -> None:
    """``client=``: None or a Dask client (an object with ``submit``)."""
    if client is not None and not callable(getattr(client, "submit", None)):
        raise TypeError(f"client: {client!r} is not a dask.distributed Client (an object with submit) nor None")


def _open(checkpoint: Any, command: str, key: str, size: Tuple[int, int]) -> Optional[_Checkpoint]:
    """The checkpoint folder of a request, None without one."""
    if checkpoint is None:
        return None
    return _Checkpoint(_checkpoint_path(checkpoint), command, key, size)


def _run_range(command: str, args: Tuple[Any, ...], start: int, end: int) -> bytes:
    """A task: the partial result of units ``start..end`` (runs on a worker)."""
    return _v2ref._units_run(command, args, start, end)


def _plan_ranges(missing: Sequence[Tuple[int, int]], chunk: int) -> List[Tuple[int, int]]:
    """The ranges of at most ``chunk`` units that cover the ``missing`` gaps."""
    out = []
    for first, last in missing:
        for start in range(first, last, chunk):
            out.append((start, min(start + chunk, last)))
    return out


def _chunk_units(units: int, client: Any, chunk_units: Optional[int]) -> int:
    if chunk_units is not None:
        if isinstance(chunk_units, bool) or not isinstance(chunk_units, int) or chunk_units < 1:
            raise ValueError(f"chunk_units: {chunk_units!r} is not an integer >= 1")
        return chunk_units
    threads = 1
    if client is not None:
        nthreads = getattr(client, "nthreads", None)
        if not callable(nthreads):
            raise TypeError(f"client: {client!r} is not a dask.distributed Client (it has no nthreads)")
        threads = max(1, sum(nthreads().values()))
    return max(MIN_UNITS_PER_TASK, _math.ceil(units / (TASKS_PER_THREAD * threads)))


def _missing(units: int, have: Sequence[Tuple[int, int]]) -> Tuple[List[Tuple[int, int]], List[Tuple[int, int]]]:
    """(ranges kept, gaps): non-overlapping found ranges in order, and the
    units none of them covers."""
    kept, gaps, covered = [], [], 0
    for start, end in sorted(have):
        if start < covered or end > units:
            continue
        if start > covered:
            gaps.append((covered, start))
        kept.append((start, end))
        covered = end
    if covered < units:
        gaps.append((covered, units))
    return kept, gaps


def _run_units(
    command: str,
    args: Tuple[Any, ...],
    client: Any = None,
    checkpoint: Any = None,
    chunk_units: Optional[int] = None,
) -> Tuple[Any, int]:
    """``(answer, ranges computed)`` of ``command`` run in ranges of units."""
    ordered, computed = _partials(command, args, client, checkpoint, chunk_units)
    return _v2ref._units_reduce(command, args, ordered), computed


def _partials(
    command: str,
    args: Tuple[Any, ...],
    client: Any = None,
    checkpoint: Any = None,
    chunk_units: Optional[int] = None,
) -> Tuple[List[bytes], int]:
    """``(partial results in unit order, ranges computed)`` of ``command``."""
    _check_client(client)
    units, key, size = _v2ref._units_count(command, args)
    chunk = _chunk_units(units, client, chunk_units)
    store = _open(checkpoint, command, key, size)
    try:
        found = store.load(args) if store is not None else {}
        kept, gaps = _missing(units, list(found))
        todo = _plan_ranges(gaps, chunk)
        results = {r: found[r] for r in kept}
        for (start, end), data in _compute(command, args, key, todo, client):
            if store is not None:
                store.save(start, end, data)
            results[(start, end)] = data
    finally:
        if store is not None:
            store.close()
    return [results[r] for r in sorted(results)], len(todo)


def _compute(command: str, args: Tuple[Any, ...], key: str, todo: List[Tuple[int, int]], client: Any):
    """Yields ``((start, end), bytes)`` for each range of ``todo`` as it
    finishes: Dask tasks with ``client``, else here one after another."""
    if client is None:
        for start, end in todo:
            yield (start, end), _run_range(command, args, start, end)
        return
    from distributed import as_completed

    futures = [
        client.submit(
            _run_range,
            command,
            args,
            start,
            end,
            key=f"v2ref-{command}-{key}-{start}-{end}",
            pure=True,
            retries=RETRIES,
        )
        for start, end in todo
    ]
    ranges = {f.key: r for f, r in zip(futures, todo)}
    try:
        for future in as_completed(futures):
            yield ranges[future.key], future.result()
    finally:
        # Interrupted: the tasks still pending are dropped. (Finished ones
        # are only released, by reference count: cancelling them would race
        # with a rerun that submits the same keys at once.)
        pending = [f for f in futures if not f.done()]
        if pending:
            client.cancel(pending)


def _target_rows(row: Tuple[Any, ...], throughput: Any, args: Dict[str, Any]) -> List[Dict[str, Any]]:
    """A task: the table row of one list row as read (runs on a worker; it
    carries its row, not the list)."""
    return _v2ref.plan_targets(None, None, throughput, **args, rows=[row])


def _plan_targets(
    path: Optional[str],
    text: Optional[str],
    throughput: Any,
    args: Dict[str, Any],
    client: Any,
    report: Any = None,
    checkpoint: Any = None,
) -> List[Dict[str, Any]]:
    """``plan_targets`` row by row: a Dask task each with ``client``, else
    here one after another. The list is read once, here; every row is
    planned alone (its seed keyed by its content), so the rows joined in
    order are the one-process table, bit for bit. ``report(done, total)``
    after each row finished, if given. With ``checkpoint``, each row's
    table row is kept there as it finishes, and the rows found there (of
    this very list and these arguments) are not planned again."""
    _check_client(client)
    if checkpoint is not None:
        checkpoint = _checkpoint_path(checkpoint)
    rows = _v2ref._targets_rows(path, text)
    store = None
    if checkpoint is not None:
        store = _open(checkpoint, "targets", _targets_key(rows, throughput, args), (0, 0))
    try:
        done = store.load_records(rows) if store is not None else {}
        todo = [i for i in range(len(rows)) if i not in done]
        for i, part in _target_parts(rows, throughput, args, todo, client):
            if store is not None:
                store.save(i, i + 1, _record_bytes(store.key, i, rows[i][0], rows[i][1], part))
            done[i] = part
            if report is not None:
                report(len(done), len(rows))
    finally:
        if store is not None:
            store.close()
    return [row for i in range(len(rows)) for row in done[i]]


def _target_parts(rows: Sequence[Tuple[Any, ...]], throughput: Any, args: Dict[str, Any], todo: List[int], client: Any):
    """Yields ``(row, its table rows)`` for each row of ``todo`` as it
    finishes."""
    if client is None:
        for i in todo:
            yield i, _target_rows(rows[i], throughput, args)
        return
    from distributed import as_completed

    futures = {
        client.submit(_target_rows, rows[i], throughput, args, pure=True, retries=RETRIES): i
        for i in todo
    }
    for future in as_completed(list(futures)):
        yield futures[future], future.result()


def _targets_key(rows: Sequence[Tuple[Any, ...]], throughput: Any, args: Dict[str, Any]) -> str:
    """The key of a target list's checkpoint entries: the list's rows as
    read, the shared keywords, the spectrum CSV's table (its content, not
    its path) and the package's version (a change to any plans every row
    again)."""
    spectrum = _v2ref._spectrum_key(args["physical"])
    blob = _json.dumps([_v2ref.__version__, rows, throughput, args, spectrum], sort_keys=True, default=repr)
    return _hashlib.sha256(blob.encode()).hexdigest()[:32]


#: :func:`v2ref.plan`'s keywords (as the extension takes them) that its
#: verification's tasks rebuild the plan's inputs from.
_PLAN_INPUTS = (
    "physical", "samples_per_fringe", "photon_rate_per_s", "dead_time_s", "fringe_hz",
    "stroke_um", "target_sigma_v2", "time_budget_s", "scans", "seed", "diameter_err_mas",
    "bias", "magnitude", "frame_rate_hz", "instrument",
)


def _plan_verify_units(arguments: Dict[str, Any], client: Any, checkpoint: Any):
    """``plan``'s ``verify_units``: called by the extension, once the plan
    has recommended a point (f, Δx, n scans), with the number of
    observations; returns the partial results of the verification's
    batches of piston sequences in order, a task each (each rebuilds the
    plan's inputs from its keywords, in milliseconds, not the plan)."""
    _check_client(client)
    if checkpoint is not None:
        checkpoint = _checkpoint_path(checkpoint)
    kw = {k: arguments[k] for k in _PLAN_INPUTS if k in arguments}
    threads = arguments["threads"] or (1 if client is not None else 0)

    def units(fringe_hz: float, stroke_um: float, scans: int, observations: int) -> List[bytes]:
        args = (kw, fringe_hz, stroke_um, scans, observations, threads)
        return _partials("verify", args, client, checkpoint, 1)[0]

    return units
