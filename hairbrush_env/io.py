"""Atomic file output: results are written to a temporary sibling and renamed, so an interrupt loses nothing
(the previous file stays intact until the new one is complete)."""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import tempfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; on success it replaces ``path`` atomically (``os.replace``)."""
    final = Path(path)
    final.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{final.name}.", suffix=".tmp" + final.suffix, dir=final.parent)
    os.close(fd)
    tmp_path = Path(tmp)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp_path, 0o666 & ~umask)  # mkstemp creates 0600; give results the usual permissions
    try:
        yield tmp_path
        os.replace(tmp_path, final)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


def write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Atomically write ``text`` (UTF-8) to ``path``."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def write_json(path: str | os.PathLike[str], obj: Any) -> Path:
    """Atomically write ``obj`` as indented JSON (numpy scalars/arrays converted)."""

    def default(o: Any) -> Any:
        if hasattr(o, "tolist"):
            return o.tolist()
        raise TypeError(f"not JSON serializable: {type(o).__name__}")

    return write_text(path, json.dumps(obj, indent=2, default=default) + "\n")


def write_csv_rows(
    path: str | os.PathLike[str], rows: Iterable[dict[str, Any]], columns: Sequence[str]
) -> Path:
    """Atomically write ``rows`` (dicts; keys outside ``columns`` are ignored) as a CSV with a header."""
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=list(columns), extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return write_text(path, buf.getvalue())


def csv_text(header: Sequence[str], rows: Iterable[Sequence[Any]]) -> str:
    """CSV text of ``rows`` under ``header``, floats to 6 significant digits (for :func:`write_text`)."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(header)
    for row in rows:
        writer.writerow([f"{v:.6g}" if isinstance(v, float) else v for v in row])
    return buf.getvalue()


def read_csv_rows(
    path: str | os.PathLike[str],
    *,
    floats: Sequence[str] = (),
    ints: Sequence[str] = (),
    bools: Sequence[str] = (),
    fallbacks: Mapping[str, str] | None = None,
) -> list[dict[str, Any]]:
    """Rows of a CSV written by :func:`write_csv_rows`, with the named columns converted back (a named column the
    file does not have, e.g. one added after it was written, stays absent). ``fallbacks`` maps a float column added
    later to the converted column that stood for it before: where the file has no value for it, it takes that one
    (``{"pull_max_force": "max_force"}``: before v10 a stroke read its whole pull)."""
    rows = []
    with open(path, newline="") as fh:
        for row in csv.DictReader(fh):
            row.update({k: float(row[k]) for k in floats if k in row})
            row.update({k: int(row[k]) for k in ints if k in row})
            row.update({k: row[k] == "True" for k in bools if k in row})
            for k, old in (fallbacks or {}).items():
                value = row.get(k, "")
                row[k] = float(value) if value not in ("", "None", None) else row[old]
            rows.append(row)
    return rows
