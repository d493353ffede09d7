"""Files of one combing run: :func:`write_run` (curves and link-density snapshots as CSV, summary as JSON, figure)."""

from __future__ import annotations

from .plots import plot_run
from .result import CombingResult

__all__ = ["write_run"]


def write_run(result: CombingResult, out_dir, *, stem: str = "combing") -> list:
    """Write ``<stem>.csv`` (curves), ``<stem>_snapshots.csv``, ``<stem>.json`` (summary) and ``<stem>.png``."""
    from pathlib import Path

    from ...io import csv_text, write_json, write_text

    out = Path(out_dir)
    header, table = result.csv_rows()
    paths = [write_text(out / f"{stem}.csv", csv_text(header, table.tolist()))]
    rows = [
        [x, float(si), float(v)]
        for x, (s, dl) in result.snapshots.items()
        for si, v in zip(s, dl, strict=True)
    ]
    paths.append(
        write_text(out / f"{stem}_snapshots.csv", csv_text(["x", "s_m", "dlambda_over_lambda0"], rows))
    )
    paths.append(write_json(out / f"{stem}.json", result.summary()))
    plot_run(result, out / f"{stem}.png")
    paths.append(out / f"{stem}.png")
    return paths
