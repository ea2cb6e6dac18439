"""Progress of :func:`v2ref.plan_targets` (``progress=``): a callable
told ``(done, total)`` after each target, or ``True`` for a line on
stderr at most once a second with the elapsed time and an estimate of the
time left (as ``v2ref plan --targets`` shows a bar and an ETA)."""

import sys as _sys
import time as _time
from typing import Any, Callable, Optional


def _clock(seconds: float) -> str:
    s = int(round(seconds))
    h, m = divmod(s // 60, 60)
    return f"{h}:{m:02d}:{s % 60:02d}" if h else f"{m}:{s % 60:02d}"


class Line:
    """``(done, total)`` as a line on ``stream``, at most one a second
    (``clock`` in seconds), the last always; the time left is the mean
    time of a target so far times the targets left."""

    def __init__(self, stream: Any = None, clock: Callable[[], float] = _time.monotonic):
        self.stream = stream if stream is not None else _sys.stderr
        self.clock = clock
        self.start = clock()
        self.last: Optional[float] = None

    def __call__(self, done: int, total: int) -> None:
        now = self.clock()
        if done < total and self.last is not None and now - self.last < 1.0:
            return
        self.last = now
        elapsed = now - self.start
        left = elapsed / done * (total - done) if done else float("nan")
        tail = "done" if done == total else f"about {_clock(left)} left"
        print(f"plan_targets: {done}/{total} targets, {_clock(elapsed)} elapsed, {tail}", file=self.stream, flush=True)


def reporter(progress: Any) -> Optional[Callable[[int, int], None]]:
    """The ``(done, total)`` callable of ``progress`` (None: no progress)."""
    if progress is None or progress is False:
        return None
    if progress is True:
        return Line()
    if callable(progress):
        return progress
    raise TypeError(f"progress: {progress!r} is not a bool or a callable (done, total)")
