"""Recordings (rerun) and figures (matplotlib) used by the CLI and scripts.

Heavy imports happen inside the functions, so importing this module is cheap and the library never selects a
GUI backend: figures are drawn on an Agg canvas via :class:`matplotlib.figure.Figure`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence

import numpy as np

from .io import atomic_path

# Distinct, colour-blind-friendly colours (Okabe–Ito) for strands and policies.
PALETTE = ["#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442", "#000000"]


def rgb(color: str) -> tuple[int, int, int]:
    """``"#RRGGBB"`` → (r, g, b) bytes."""
    c = color.lstrip("#")
    return int(c[0:2], 16), int(c[2:4], 16), int(c[4:6], 16)


def new_figure(ncols: int = 1, nrows: int = 1, *, width: float = 5.0, height: float = 4.0, **subplot_kw):
    """A headless figure and its axes (no pyplot state, no backend selection)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width * ncols, height * nrows), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, subplot_kw=subplot_kw or None)
    return fig, axes


def save_figure(fig, path: str | os.PathLike[str], *, dpi: int = 120) -> None:
    """Atomically save a figure as PNG (or any format matplotlib infers from the suffix)."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=str(path).rsplit(".", 1)[-1])


def record_curves(
    path: str | os.PathLike[str],
    frames: Sequence[Mapping[str, np.ndarray]],
    *,
    times: Sequence[float] | None = None,
    scalars: Mapping[str, Sequence[float]] | None = None,
    application_id: str = "hairbrush_env",
) -> None:
    """Write a rerun recording (.rrd) of named 3-D polylines over time, plus optional scalar time series.

    ``frames[k]`` maps an entity name to an ``(n, 3)`` polyline at time ``times[k]`` (default: k).
    """
    import rerun as rr

    rec = rr.RecordingStream(application_id)
    times = list(range(len(frames))) if times is None else list(times)
    with atomic_path(path) as tmp:
        rec.save(tmp)
        for k, (t, frame) in enumerate(zip(times, frames, strict=True)):
            rec.set_time("t", duration=float(t))
            for i, (name, pts) in enumerate(frame.items()):
                rec.log(
                    name, rr.LineStrips3D([np.asarray(pts, dtype=np.float32)], colors=[rgb(PALETTE[i % 8])])
                )
            for name, series in (scalars or {}).items():
                rec.log(name, rr.Scalars([float(series[k])]))
        rec.flush()
        rec.disconnect()
