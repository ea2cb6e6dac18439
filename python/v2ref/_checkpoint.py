"""A checkpoint folder of :mod:`v2ref.dask`: its entries written whole,
read without following links, and used only when their checksum, their
key and their place all agree (docs/dask.md says what is refused and what
is computed again).

A partial result (bytes of the library's units) carries its own checksum,
checked by the extension; a target list's record carries a BLAKE2b digest
of its JSON body (``hashlib``: a well-known function in the standard
library), the body naming the list's key, the row and the row's line and
name. Both detect damage and mix-ups; neither stops a writer of the folder
from forging an entry (``docs/threat-model.md``), which is why entries of
another user are never read.
"""

import errno as _errno
import hashlib as _hashlib
import json as _json
import os as _os
import re as _re
import secrets as _secrets
import stat as _stat
import warnings as _warnings
from typing import Any, Dict, List, Optional, Sequence, Tuple

from . import _v2ref

_SUFFIX = ".partial"

#: Largest checkpoint entry of one target list row read, bytes.
MAX_RECORD_BYTES = 1 << 20

#: The first bytes of a target list's record (format version 2: the
#: digest follows, then a line end and the JSON body).
_RECORD_MAGIC = b"v2ref-targets-record-2 "

#: Times a temporary's name is drawn again when one is already there.
_TEMPORARY_TRIES = 8


def entry_name(command: str, key: str, start: int, end: int) -> str:
    return f"v2ref-{command}-{key}-{start}-{end}{_SUFFIX}"


def checked_path(checkpoint: Any) -> str:
    """``checkpoint=`` as a path, refused by name unless it is one."""
    if isinstance(checkpoint, bool) or not isinstance(checkpoint, (str, bytes, _os.PathLike)):
        raise TypeError(f"checkpoint: {checkpoint!r} is not a folder's path (str or os.PathLike)")
    return _os.fsdecode(_os.fspath(checkpoint))


def checkpoint_path(checkpoint: Any) -> str:
    """``checkpoint=`` as a folder's path, the folder made if it is missing
    (its parent must exist): refused by name before anything is computed."""
    path = checked_path(checkpoint)
    try:
        _os.mkdir(path, 0o700)
    except FileExistsError:
        pass
    except OSError as e:
        raise ValueError(f"checkpoint: the folder {path!r} cannot be made ({e.strerror}); its parent must exist") from None
    if not _os.path.isdir(path):
        raise ValueError(f"checkpoint: {path!r} is not a folder")
    return path


def _record_digest(body: bytes) -> str:
    return _hashlib.blake2b(body, digest_size=16, person=b"v2ref-targets").hexdigest()


def record_bytes(key: str, row: int, line: int, name: str, table: List[Dict[str, Any]]) -> bytes:
    """A target list row's record: its table rows and what they answer."""
    body = _json.dumps({"key": key, "row": row, "line": line, "name": name, "table": table}, sort_keys=True).encode()
    return _RECORD_MAGIC + _record_digest(body).encode() + b"\n" + body


class Checkpoint:
    """A checkpoint folder, opened once (entries are reached through it)."""

    def __init__(self, path: str, command: str, key: str, size: Tuple[int, int]):
        flags = _os.O_RDONLY | getattr(_os, "O_DIRECTORY", 0) | getattr(_os, "O_CLOEXEC", 0)
        try:
            self.fd = _os.open(path, flags)
        except OSError as e:
            raise ValueError(f"checkpoint: the folder {path!r} cannot be opened ({e.strerror})") from None
        self.path, self.command, self.key = path, command, key
        # A partial of n units is size[0] + n * size[1] bytes: nothing
        # longer is read.
        self.size = size
        self._pattern = _re.compile(
            rf"v2ref-{_re.escape(command)}-{key}-([0-9]{{1,20}})-([0-9]{{1,20}}){_re.escape(_SUFFIX)}"
        )

    def close(self) -> None:
        _os.close(self.fd)

    def _refuse(self, name: str, why: str) -> ValueError:
        return ValueError(
            f"checkpoint: {_os.path.join(self.path, name)!r} {why}; delete it to compute its part again"
        )

    def _entries(self):
        """``(name, start, end)`` of each entry of this request in the
        folder (other names are left alone)."""
        try:
            names = _os.listdir(self.fd)
        except OSError as e:
            raise ValueError(f"checkpoint: the folder {self.path!r} cannot be listed ({e.strerror})") from None
        for name in sorted(names):
            m = self._pattern.fullmatch(name)
            if m is not None:
                yield name, int(m.group(1)), int(m.group(2))

    def load(self, args: Tuple[Any, ...]) -> Dict[Tuple[int, int], bytes]:
        """The partial results of this request found in the folder, by range
        (their checksum, key and range checked by the extension)."""
        found = {}
        for name, start, end in self._entries():
            data = self._read(name, self.size[0] + max(end - start, 0) * self.size[1])
            if data is None:
                continue
            try:
                rng = _v2ref._units_check(self.command, args, data)
            except ValueError as e:
                raise self._refuse(name, f"is not a partial result of this request ({e})") from None
            if rng != (start, end):
                raise self._refuse(name, f"holds units {rng[0]}..{rng[1]}, not those of its name")
            found[rng] = data
        return found

    def load_records(self, rows: Sequence[Tuple[Any, ...]]) -> Dict[int, List[Dict[str, Any]]]:
        """The table row of each list row found in the folder, by row: a
        record whose digest, key, row, line and name are this list's, and
        whose table is one row of that line and name."""
        found = {}
        for name, start, end in self._entries():
            data = self._read(name, MAX_RECORD_BYTES, exact=False)
            if data is None:
                continue
            if end != start + 1 or start >= len(rows):
                raise self._refuse(name, f"is not one row of a list of {len(rows)}")
            line, target = rows[start][0], rows[start][1]
            found[start] = self._record(name, data, start, line, target)
        return found

    def _record(self, name: str, data: bytes, row: int, line: int, target: str) -> List[Dict[str, Any]]:
        head, _, body = data.partition(b"\n")
        if not head.startswith(_RECORD_MAGIC) or head[len(_RECORD_MAGIC):] != _record_digest(body).encode():
            raise self._refuse(name, "is damaged or not a v2ref target record (its digest does not match its content)")
        try:
            record = _json.loads(body)
        except (ValueError, RecursionError) as e:
            raise self._refuse(name, f"holds no readable record ({type(e).__name__})") from None
        expected = {"key": self.key, "row": row, "line": line, "name": target}
        if not isinstance(record, dict) or any(record.get(k) != v for k, v in expected.items()):
            raise self._refuse(name, "is the record of another list, keywords or row")
        table = record.get("table")
        if not (isinstance(table, list) and len(table) == 1 and isinstance(table[0], dict)):
            raise self._refuse(name, "does not hold exactly one table row")
        if table[0].get("line") != line or table[0].get("TARGET") != target:
            raise self._refuse(name, f"holds the table row of another line than {line} ({target!r})")
        return table

    def _read(self, name: str, size: int, exact: bool = True) -> Optional[bytes]:
        """The bytes of entry ``name``, or None for an entry of another user
        (never trusted: its part is computed again, with a warning)."""
        flags = _os.O_RDONLY | _os.O_NOFOLLOW | getattr(_os, "O_NONBLOCK", 0) | getattr(_os, "O_CLOEXEC", 0)
        try:
            fd = _os.open(name, flags, dir_fd=self.fd)
        except OSError as e:
            raise self._refuse(name, f"cannot be read as a regular file (a link is never followed): {e.strerror}") from None
        try:
            st = _os.fstat(fd)
            if not _stat.S_ISREG(st.st_mode):
                raise self._refuse(name, "is not a regular file")
            if st.st_uid != _os.geteuid():
                _warnings.warn(
                    f"checkpoint: {_os.path.join(self.path, name)!r} belongs to another user "
                    f"(uid {st.st_uid}): not read, its part computed again",
                    stacklevel=4,
                )
                return None
            if exact and st.st_size != size:
                raise self._refuse(name, f"is {st.st_size} bytes, not the {size} of its units' results")
            if st.st_size > size:
                raise self._refuse(name, f"is {st.st_size} bytes, more than the {size} an entry holds")
            chunks, left = [], size
            while left > 0:
                chunk = _os.read(fd, min(left, 1 << 20))
                if not chunk:
                    break
                chunks.append(chunk)
                left -= len(chunk)
            return b"".join(chunks)
        except OSError as e:
            raise self._refuse(name, f"cannot be read ({e.strerror})") from None
        finally:
            _os.close(fd)

    def save(self, start: int, end: int, data: bytes) -> None:
        """Places the entry of ``start..end`` atomically; an entry already
        at its name (the same range of a concurrent run, or anything else)
        is left as it is."""
        name = entry_name(self.command, self.key, start, end)
        try:
            fd, tmp = self._temporary(name)
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
        except OSError as e:
            raise ValueError(f"checkpoint: {_os.path.join(self.path, name)!r} cannot be written ({e.strerror})") from None

    def _temporary(self, name: str) -> Tuple[int, str]:
        """A temporary created new beside ``name`` (its name drawn again
        while another file holds it)."""
        flags = _os.O_WRONLY | _os.O_CREAT | _os.O_EXCL | _os.O_NOFOLLOW | getattr(_os, "O_CLOEXEC", 0)
        for _ in range(_TEMPORARY_TRIES):
            tmp = f".v2ref-tmp-{_os.getpid()}-{_secrets.token_hex(6)}-{name}"
            try:
                return _os.open(tmp, flags, 0o644, dir_fd=self.fd), tmp
            except FileExistsError:
                continue
        raise OSError(_errno.EEXIST, f"{_TEMPORARY_TRIES} temporaries' names taken")
