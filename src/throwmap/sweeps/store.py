"""A sweep's results on disk: a directory of Parquet files, one per chunk of design points, and a manifest.

Layout of ``OUT``::

    OUT/_manifest.json        the sweep's content hash, target, design size, columns (written first)
    OUT/part-000000.parquet   chunk 0: one row per design point, written atomically
    OUT/part-000001.parquet   …

Each ``part-*.parquet`` is written to a temporary name in ``OUT`` (a leading ``.``), fsync'ed and renamed
(:func:`os.replace`): a file with its final name is complete. A restart lists the files that exist and
computes only the missing chunks; a temporary file left by a killed run is deleted. Every file has the same
Arrow schema (from the manifest), so ``pyarrow.parquet.read_table(OUT)`` or ``pandas.read_parquet(OUT)``
reads the whole sweep (files starting with ``_`` or ``.`` are skipped by both).

The manifest holds the sweep's content hash (:func:`throwmap.sweeps.schema.spec_hash`): a sweep whose
content differs from the one stored in ``OUT`` is refused, naming the first key that differs.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

from ..version import __version__
from ..errors import InvalidStateError, shown
from ..io.files import make_directory
from .schema import jsonable

__all__ = ["MANIFEST", "FORMAT", "column_types", "prepare_out", "finished_chunks", "write_chunk", "read_table",
           "count_rows", "part_path"]

MANIFEST = "_manifest.json"
FORMAT = "throwmap-sweep/1"
_PART = re.compile(r"^part-(\d{6,})\.parquet$")
COMMON_COLUMNS = {"point": "int64", "seed": "int64", "version": "string", "elapsed_s": "float64", "error": "string"}
"""Columns of every sweep: the design point's index, its seed, ``throwmap.__version__`` of the run that
computed it, the wall time (s) and the error (None unless the library refused the point)."""


def part_path(out: Path, chunk: int) -> Path:
    return Path(out) / f"part-{chunk:06d}.parquet"


def _value_type(values) -> str:
    """The Arrow type of a parameter column: bool, int64, float64 or string; values of mixed or nested types
    (lists, tables) are stored as JSON text (``json``)."""
    seen = {type(v) for v in values if v is not None}
    if not seen:
        return "string"
    if seen == {bool}:
        return "bool"
    if seen == {int}:
        return "int64"
    if seen <= {int, float}:
        return "float64"
    if seen == {str}:
        return "string"
    return "json"


def column_types(names, points, result_columns: dict) -> dict:
    """The ordered column → type map of a sweep's rows: ``point``, the parameters, ``seed``, ``version``, the
    target's result columns, ``elapsed_s``, ``error``. A parameter named like another column is refused."""
    cols = {"point": "int64"}
    for j, name in enumerate(names):
        reserved = set(COMMON_COLUMNS) | set(result_columns)
        if name in reserved:
            raise InvalidStateError(f"parameters.{name}", f"is also a result column ({', '.join(sorted(reserved))}): "
                                                          f"these names are taken")
        cols[name] = _value_type([p[j] for p in points])
    cols.update({"seed": "int64", "version": "string"})
    cols.update(result_columns)
    cols.update({"elapsed_s": "float64", "error": "string"})
    return cols


def _arrow_schema(columns: dict):
    import pyarrow as pa

    types = {"int64": pa.int64(), "float64": pa.float64(), "string": pa.string(), "bool": pa.bool_(),
             "json": pa.string()}
    return pa.schema([(k, types[t]) for k, t in columns.items()])


def _fsync_dir(path: Path) -> None:
    try:
        fd = os.open(path, os.O_RDONLY)
    except OSError:  # pragma: no cover - platforms without directory fds
        return
    try:
        os.fsync(fd)
    except OSError:  # pragma: no cover
        pass
    finally:
        os.close(fd)


def _atomic_text(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    with open(tmp, "w", encoding="utf-8") as fh:
        fh.write(text)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)
    _fsync_dir(path.parent)


def _first_difference(a, b, prefix: str = "") -> str:
    if isinstance(a, dict) and isinstance(b, dict):
        for k in list(a) + [k for k in b if k not in a]:
            if a.get(k) != b.get(k):
                return _first_difference(a.get(k), b.get(k), f"{prefix}.{k}" if prefix else str(k))
    return prefix or "sweep"


def prepare_out(out, manifest: dict) -> dict:
    """Create ``out`` (never a missing folder above it) with its manifest, or check the one there: the same
    ``sweep_sha256`` or a one-line :class:`~throwmap.errors.InvalidStateError` on ``out`` naming the first sweep
    key that differs. Returns the stored manifest (its ``version`` is the first run's)."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InvalidStateError("out", f"{str(out)!r} is a file, not a directory")
    path = out / MANIFEST
    if path.exists():
        try:
            stored = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError) as err:
            raise InvalidStateError("out", f"{str(path)!r} is not a sweep manifest ({err})") from None
        if stored.get("format") != FORMAT:
            raise InvalidStateError("out", f"{str(path)!r} is not a {FORMAT} manifest (format {shown(stored.get('format'))})")
        if stored.get("sweep_sha256") != manifest["sweep_sha256"]:
            where = _first_difference(stored.get("spec") or {}, manifest["spec"])
            raise InvalidStateError("out", f"{str(out)!r} holds another sweep (sha256 {stored.get('sweep_sha256', '?')[:12]}…, "
                                           f"this one {manifest['sweep_sha256'][:12]}…; first difference: {where}): "
                                           f"use another --out, or delete it to start again")
        return stored
    if out.exists() and any(_PART.match(p.name) for p in out.iterdir()):
        raise InvalidStateError("out", f"{str(out)!r} holds Parquet parts but no {MANIFEST}: not a sweep of this version")
    make_directory(out, "out")  # only it: a missing folder above it is refused
    manifest = {"format": FORMAT, "version": __version__, **manifest}
    _atomic_text(path, json.dumps(manifest, indent=2, allow_nan=False) + "\n")
    return manifest


def finished_chunks(out, n_chunks: int, expected_rows) -> set:
    """The chunks whose Parquet file exists in ``out`` with the rows it should have (``expected_rows(c)``); a
    temporary file of a killed run is deleted, and so is a part that cannot be read (it is then recomputed)."""
    import pyarrow.parquet as pq

    out = Path(out)
    done = set()
    if not out.is_dir():
        return done
    for p in out.iterdir():
        if p.name.startswith(".part-") and p.name.endswith(".tmp"):
            p.unlink(missing_ok=True)
            continue
        m = _PART.match(p.name)
        if not m:
            continue
        c = int(m.group(1))
        try:
            ok = c < n_chunks and pq.read_metadata(p).num_rows == expected_rows(c)
        except (OSError, ValueError):
            ok = False
        if ok:
            done.add(c)
        else:
            p.unlink(missing_ok=True)
    return done


def write_chunk(out, chunk: int, rows: list, columns: dict) -> Path:
    """Write chunk ``chunk``'s rows (dicts with every column) as ``part-<chunk>.parquet``, atomically."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    data = {}
    for name, kind in columns.items():
        col = [r.get(name) for r in rows]
        if kind == "json":
            col = [None if v is None else json.dumps(jsonable(v), sort_keys=True, allow_nan=False) for v in col]
        elif kind == "float64":
            col = [None if v is None else float(v) for v in col]
        data[name] = col
    table = pa.table(data, schema=_arrow_schema(columns))
    path = part_path(out, chunk)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        pq.write_table(table, tmp)
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    _fsync_dir(path.parent)
    return path


def read_table(out):
    """Every stored row of the sweep in ``out`` as one :class:`pyarrow.Table`, sorted by ``point``."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    out = Path(out)
    parts = sorted(p for p in out.iterdir() if _PART.match(p.name)) if out.is_dir() else []
    if not parts:
        stored = json.loads((out / MANIFEST).read_text()) if (out / MANIFEST).exists() else None
        return _arrow_schema(stored["columns"]).empty_table() if stored else pa.table({})
    table = pa.concat_tables([pq.read_table(p) for p in parts])
    return table.sort_by("point")


def count_rows(out) -> int:
    """Rows stored in ``out`` (from the Parquet footers, nothing else read)."""
    import pyarrow.parquet as pq

    out = Path(out)
    if not out.is_dir():
        return 0
    return sum(pq.read_metadata(p).num_rows for p in out.iterdir() if _PART.match(p.name))
