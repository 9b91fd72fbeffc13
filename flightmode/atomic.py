"""The one atomic writer: a file or a folder appears at its final name complete, or not at all.

Every writer builds its output under a hidden temporary name beside the target (same folder, so the
same file system: :func:`os.replace` is then an atomic rename, POSIX ``rename(2)``) and renames it
into place; a failure removes the temporary. A reader never sees half a file, and a killed process
leaves only hidden ``.NAME.tmp-PID-XXXXXXXX`` entries, which :data:`TMP_GLOB` finds (the dataset
writer sweeps them before resuming).

    write_with(path, fn)     fn(tmp_path) writes the file (pyarrow, matplotlib, rerun, ...)
    write_text / write_bytes / write_json / write_parquet     the common cases
    staged_folder(path)      a context manager yielding a folder renamed onto ``path`` on success
    read_parquet(path)       read back what write_parquet wrote, its page checksums checked

Parquet is written with a CRC-32 of every page (``write_page_checksum``), which :func:`read_parquet`
checks: a flipped bit is an error naming the file, not a wrong number read as data.

No existing writer calls ``fsync``, and none here does: the rename guarantees that a reader sees
the old or the new file whole; durability across a power cut is not asked for.
"""

from __future__ import annotations

import json
import os
import shutil
import uuid
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

TMP_GLOB = ".*.tmp-*"  # what tmp_name makes, for a sweep of a killed writer's leftovers


def tmp_name(path: str | os.PathLike) -> Path:
    """A fresh hidden temporary name beside ``path``: ``.NAME.tmp-PID-XXXXXXXX`` (8 hex digits of a
    UUID4, so two threads or processes writing one target never share a temporary)."""
    path = Path(path)
    return path.with_name(f".{path.name}.tmp-{os.getpid()}-{uuid.uuid4().hex[:8]}")


def _remove(p: Path) -> None:
    if p.is_dir() and not p.is_symlink():
        shutil.rmtree(p, ignore_errors=True)
    else:
        p.unlink(missing_ok=True)


def write_with(path: str | os.PathLike, write: Callable[[Path], Any], *, mkdir: bool = True) -> Path:
    """``write(tmp)`` writes the file at a temporary name beside ``path``; it is then renamed onto
    ``path`` (replacing any file there). On any failure the temporary is removed and the error
    raised; ``path`` is untouched. ``mkdir``: create the parent folder first. Returns ``path``."""
    path = Path(path)
    if mkdir:
        path.parent.mkdir(parents=True, exist_ok=True)
    tmp = tmp_name(path)
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        _remove(tmp)
        raise
    return path


def write_text(text: str, path: str | os.PathLike, *, encoding: str = "utf-8", mkdir: bool = True) -> Path:
    """Write ``text`` (UTF-8 by default, newlines as given) to ``path`` atomically."""
    return write_bytes(text.encode(encoding), path, mkdir=mkdir)


def write_bytes(data: bytes, path: str | os.PathLike, *, mkdir: bool = True) -> Path:
    """Write ``data`` to ``path`` atomically."""
    return write_with(path, lambda tmp: tmp.write_bytes(data), mkdir=mkdir)


def write_json(
    doc: Any, path: str | os.PathLike, *, indent: int | None = 2, default=None, newline=True
) -> Path:
    """Write ``json.dumps(doc, indent=indent, default=default)`` (plus a final newline unless
    ``newline`` is False) to ``path`` atomically. The text is built before any file is opened."""
    text = json.dumps(doc, indent=indent, default=default) + ("\n" if newline else "")
    return write_text(text, path)


def write_parquet(table, path: str | os.PathLike, **options) -> Path:
    """Write a pyarrow Table to ``path`` as Parquet atomically; ``options`` go to
    ``pyarrow.parquet.write_table`` (default ``compression="zstd"``, with page checksums)."""
    import pyarrow.parquet as pq

    options.setdefault("compression", "zstd")
    options.setdefault("write_page_checksum", True)
    return write_with(path, lambda tmp: pq.write_table(table, tmp, **options))


def read_parquet(path: str | os.PathLike, what: str, **options):
    """The pyarrow Table in the Parquet file ``path``, its page checksums checked (``options`` go to
    ``pyarrow.parquet.read_table``); an :class:`~flightmode.errors.InputDataError` naming the file and
    ``what`` it was to hold if it is missing, not Parquet, cut short or damaged."""
    import pyarrow.parquet as pq

    from flightmode.errors import InputDataError

    path = Path(path)
    if not path.is_file():
        raise InputDataError(f"{path}: missing (the {what})")
    try:
        return pq.read_table(path, page_checksum_verification=True, **options)
    except Exception as e:  # pyarrow raises several types for a damaged file
        raise InputDataError(f"{path}: not a readable Parquet file, the {what} damaged ({e})") from None


@contextmanager
def staged_folder(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a fresh hidden folder beside ``path``; when the block ends without an error it is renamed
    onto ``path`` (an existing ``path`` is first renamed aside and removed after, so ``path`` is never
    missing half its files); on an error the staging folder is removed and ``path`` is untouched."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    stage = tmp_name(path)
    stage.mkdir()
    try:
        yield stage
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    if path.exists():
        trash = tmp_name(path)
        os.replace(path, trash)
        os.replace(stage, path)
        _remove(trash)
    else:
        os.replace(stage, path)


__all__ = [
    "TMP_GLOB",
    "tmp_name",
    "write_with",
    "write_text",
    "write_bytes",
    "write_json",
    "write_parquet",
    "read_parquet",
    "staged_folder",
]
