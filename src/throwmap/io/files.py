"""File output: atomic writes (every file throwmap writes goes through here) and JSON-ready values.

A result file is either the old one or the complete new one, never half-written:
the data go to a temporary file in the same directory, are flushed to disk, and
the temporary file is renamed over the target with :func:`os.replace` (atomic on
POSIX and Windows when both live on one file system).

No output creates a missing folder: an output directory is made by :func:`make_directory`, which makes
that directory alone and refuses one whose folder is missing.
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

__all__ = ["atomic_write_bytes", "atomic_write_text", "make_directory"]


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


def make_directory(path: str | os.PathLike, field: str = "out") -> Path:
    """Create the output directory ``path`` unless it is there, and only it: a missing folder above it is
    refused, never made (:class:`~throwmap.errors.InvalidStateError` on ``field``: ``folder '…' does not
    exist``), as is a path that exists as something else. Returns ``path`` as a :class:`Path`."""
    from ..errors import InvalidStateError

    path = Path(path)
    try:
        path.mkdir(exist_ok=True)
    except FileNotFoundError:
        raise InvalidStateError(field, f"folder {str(path.parent)!r} does not exist") from None
    except FileExistsError:
        raise InvalidStateError(field, f"cannot create directory {str(path)!r}: it exists and is not a "
                                       f"directory") from None
    except OSError as err:
        raise InvalidStateError(field, f"cannot create directory {str(path)!r}: {err.strerror or err}") from None
    return path
