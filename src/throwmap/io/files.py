"""File output: atomic writes (every file throwmap writes goes through here) and JSON-ready values.

A result file is either the old one or the complete new one, never half-written:
the data go to a temporary file in the same directory, are flushed to disk, and
the temporary file is renamed over the target with :func:`os.replace` (atomic on
POSIX and Windows when both live on one file system).
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

__all__ = ["atomic_write_bytes", "atomic_write_text"]


def _new_file_mode() -> int:
    """Permission bits an ordinary ``open(path, "w")`` would give a new file."""
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


@contextmanager
def atomic_output(path: str | os.PathLike, suffix: str = ".tmp"):
    """Context manager yielding a temporary path beside ``path``; on success the
    file written there is synced and renamed onto ``path`` atomically.

    The parent directory must exist (it is not created). An existing target keeps
    its permission bits; a new one gets the usual ``0o666 & ~umask``. On any
    failure the temporary file is removed and the target is left untouched.
    """
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    try:
        mode = path.stat().st_mode & 0o7777
    except FileNotFoundError:
        mode = _new_file_mode()
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=directory)
    os.close(fd)
    try:
        yield Path(tmp)
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically (see :func:`atomic_output`); returns ``path`` as a :class:`Path`."""
    path = Path(path)
    with atomic_output(path) as tmp:
        tmp.write_bytes(data)
    return path


def atomic_write_text(path: str | os.PathLike, text: str, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically (UTF-8 by default); see :func:`atomic_write_bytes`."""
    return atomic_write_bytes(path, text.encode(encoding))
