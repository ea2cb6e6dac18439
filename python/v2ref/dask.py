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
only, opened without following links, their embedded key and range
checked; nothing written while reading) and computes only the missing
units.
"""

import hashlib as _hashlib
import json as _json
import math as _math
import os as _os
import re as _re
import stat as _stat
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import _v2ref

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

_SUFFIX = ".partial"

#: Largest checkpoint entry of one target list row read, bytes.
_MAX_RECORD_BYTES = 1 << 20


def _name(command: str, key: str, start: int, end: int) -> str:
    return f"v2ref-{command}-{key}-{start}-{end}{_SUFFIX}"


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
        threads = max(1, sum(client.nthreads().values()))
    return max(MIN_UNITS_PER_TASK, _math.ceil(units / (TASKS_PER_THREAD * threads)))


class _Checkpoint:
    """A checkpoint folder, opened once (entries are reached through it)."""

    def __init__(self, path: Any, command: str, key: str, size: Tuple[int, int]):
        path = _os.fspath(path)
        try:
            _os.mkdir(path)
        except FileExistsError:
            pass
        flags = _os.O_RDONLY | getattr(_os, "O_DIRECTORY", 0) | getattr(_os, "O_CLOEXEC", 0)
        try:
            self.fd = _os.open(path, flags)
        except NotADirectoryError:
            raise ValueError(f"checkpoint: {path!r} is not a folder") from None
        self.path, self.command, self.key = path, command, key
        # A partial of n units is size[0] + n * size[1] bytes: nothing
        # longer is read.
        self.size = size
        self._pattern = _re.compile(
            rf"v2ref-{_re.escape(command)}-{key}-([0-9]{{1,20}})-([0-9]{{1,20}}){_re.escape(_SUFFIX)}"
        )
        self._serial = 0

    def close(self) -> None:
        _os.close(self.fd)

    def _entries(self):
        """``(name, start, end)`` of each entry of this request in the
        folder (other names are left alone)."""
        for name in _os.listdir(self.fd):
            m = self._pattern.fullmatch(name)
            if m is not None:
                yield name, int(m.group(1)), int(m.group(2))

    def load(self, args: Tuple[Any, ...]) -> Dict[Tuple[int, int], bytes]:
        """The partial results of this request found in the folder, by range."""
        found = {}
        for name, start, end in self._entries():
            data = self._read(name, self.size[0] + max(end - start, 0) * self.size[1])
            rng = _v2ref._units_check(self.command, args, data)
            if rng != (start, end):
                raise ValueError(f"checkpoint: {name} holds units {rng[0]}..{rng[1]}, not those of its name")
            found[rng] = data
        return found

    def load_records(self, rows: int) -> Dict[int, List[Dict[str, Any]]]:
        """The table rows of a target list's rows found in the folder, by
        row: each entry at most ``_MAX_RECORD_BYTES``, JSON naming this
        checkpoint's key and its row."""
        found = {}
        for name, start, end in self._entries():
            if end != start + 1 or start >= rows:
                raise ValueError(f"checkpoint: {name} is not one row of a list of {rows}")
            record = _json.loads(self._read(name, _MAX_RECORD_BYTES, exact=False))
            if not isinstance(record, dict) or record.get("key") != self.key or record.get("row") != start:
                raise ValueError(f"checkpoint: {name} is not the row of its name for this list")
            table = record.get("table")
            if not isinstance(table, list) or not all(isinstance(r, dict) for r in table):
                raise ValueError(f"checkpoint: {name} holds no table rows")
            found[start] = table
        return found

    def _read(self, name: str, size: int, exact: bool = True) -> bytes:
        flags = _os.O_RDONLY | _os.O_NOFOLLOW | getattr(_os, "O_NONBLOCK", 0) | getattr(_os, "O_CLOEXEC", 0)
        try:
            fd = _os.open(name, flags, dir_fd=self.fd)
        except OSError as e:
            raise ValueError(f"checkpoint: {name} is not a regular file (a link is never followed): {e.strerror}") from None
        try:
            st = _os.fstat(fd)
            if not _stat.S_ISREG(st.st_mode):
                raise ValueError(f"checkpoint: {name} is not a regular file")
            if exact and st.st_size != size:
                raise ValueError(f"checkpoint: {name} is {st.st_size} bytes, not the {size} of its units' results")
            if st.st_size > size:
                raise ValueError(f"checkpoint: {name} is {st.st_size} bytes, more than the {size} an entry holds")
            chunks, left = [], size
            while left > 0:
                chunk = _os.read(fd, min(left, 1 << 20))
                if not chunk:
                    break
                chunks.append(chunk)
                left -= len(chunk)
            return b"".join(chunks)
        finally:
            _os.close(fd)

    def save(self, start: int, end: int, data: bytes) -> None:
        """Places the partial of ``start..end`` atomically; an entry already
        at its name (the same range of a concurrent run, or anything else)
        is left as it is."""
        name = _name(self.command, self.key, start, end)
        self._serial += 1
        tmp = f".v2ref-tmp-{_os.getpid()}-{self._serial}-{name}"
        flags = _os.O_WRONLY | _os.O_CREAT | _os.O_EXCL | _os.O_NOFOLLOW | getattr(_os, "O_CLOEXEC", 0)
        fd = _os.open(tmp, flags, 0o644, dir_fd=self.fd)
        try:
            try:
                view = memoryview(data)
                while view:
                    view = view[_os.write(fd, view):]
                _os.fsync(fd)
            finally:
                _os.close(fd)
            try:
                _os.link(tmp, name, src_dir_fd=self.fd, dst_dir_fd=self.fd, follow_symlinks=False)
            except FileExistsError:
                pass
        finally:
            _os.unlink(tmp, dir_fd=self.fd)
        _os.fsync(self.fd)


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
    units, key, size = _v2ref._units_count(command, args)
    chunk = _chunk_units(units, client, chunk_units)
    store = _Checkpoint(checkpoint, command, key, size) if checkpoint is not None else None
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


def _target_rows(text: str, throughput: Any, args: Dict[str, Any], start: int, end: int) -> List[Dict[str, Any]]:
    """A task: the table rows of the list's rows ``start..end`` (runs on a worker)."""
    return _v2ref.plan_targets(None, text, throughput, **args, rows=(start, end))


def _list_text(path: str) -> str:
    """The text of a target list file, read here (the workers may not see
    the path); the extension has checked it is a regular file within the
    size limit. Read as the extension reads it: UTF-8, line ends kept."""
    flags = _os.O_RDONLY | getattr(_os, "O_NONBLOCK", 0) | getattr(_os, "O_CLOEXEC", 0)
    fd = _os.open(path, flags)
    with _os.fdopen(fd, "r", encoding="utf-8", newline="") as f:
        if not _stat.S_ISREG(_os.fstat(fd).st_mode):
            raise ValueError(f"targets: {path!r} is not a regular file")
        return f.read()


def _list_of(path: Optional[str], text: Optional[str]) -> Tuple[str, int]:
    """``(text, rows)`` of a target list given as a path or as text: a
    path is read once, here (and checked as the extension checks it)."""
    rows = _v2ref._targets_count(path, text)
    if path is not None:
        text = _list_text(path)
        if _v2ref._targets_count(None, text) != rows:
            raise ValueError(f"targets: {path!r} changed while it was read")
    return text, rows


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
    here one after another. Every row is planned alone (its seed keyed by
    its content), so the rows joined in order are the one-process table,
    bit for bit. ``report(done, total)`` after each row finished, if given.
    With ``checkpoint``, each row's table rows are kept there as they
    finish, and the rows found there (of this very list and these
    arguments) are not planned again."""
    text, rows = _list_of(path, text)
    store = None
    if checkpoint is not None:
        store = _Checkpoint(checkpoint, "targets", _targets_key(text, throughput, args), (0, 0))
    try:
        done = store.load_records(rows) if store is not None else {}
        todo = [i for i in range(rows) if i not in done]
        for i, part in _target_parts(text, throughput, args, todo, client):
            if store is not None:
                store.save(i, i + 1, _json.dumps({"key": store.key, "row": i, "table": part}).encode())
            done[i] = part
            if report is not None:
                report(len(done), rows)
    finally:
        if store is not None:
            store.close()
    return [row for i in range(rows) for row in done[i]]


def _target_parts(text: str, throughput: Any, args: Dict[str, Any], todo: List[int], client: Any):
    """Yields ``(row, its table rows)`` for each row of ``todo`` as it
    finishes."""
    if client is None:
        for i in todo:
            yield i, _target_rows(text, throughput, args, i, i + 1)
        return
    from distributed import as_completed

    futures = {
        client.submit(_target_rows, text, throughput, args, i, i + 1, pure=True, retries=RETRIES): i
        for i in todo
    }
    for future in as_completed(list(futures)):
        yield futures[future], future.result()


def _targets_key(text: str, throughput: Any, args: Dict[str, Any]) -> str:
    """The key of a target list's checkpoint entries: the list's text, the
    shared keywords and the package's version (a change to any plans
    every row again)."""
    blob = _json.dumps([_v2ref.__version__, text, throughput, args], sort_keys=True, default=repr)
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
    kw = {k: arguments[k] for k in _PLAN_INPUTS if k in arguments}
    threads = arguments["threads"] or (1 if client is not None else 0)

    def units(fringe_hz: float, stroke_um: float, scans: int, observations: int) -> List[bytes]:
        args = (kw, fringe_hz, stroke_um, scans, observations, threads)
        return _partials("verify", args, client, checkpoint, 1)[0]

    return units
