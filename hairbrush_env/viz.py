"""Recordings (rerun) and figures (matplotlib) used by the CLI and scripts.

Heavy imports happen inside the functions, so importing this module is cheap and the library never selects a
GUI backend: figures are drawn on an Agg canvas via :class:`matplotlib.figure.Figure`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence

import numpy as np

from .constants import PAIN_THRESHOLD_N
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


class EpisodeRecorder:
    """Rerun recording of brushing episodes: strands as line strips coloured by pair, the brush position, the
    webcam image, the load-cell force as a time series and the entanglement per stroke.

    Everything goes to one ``.rrd`` file written atomically on :meth:`close`. Create one only when recording is
    wanted — a run without a recorder pays nothing.
    """

    def __init__(self, path: str | os.PathLike[str], *, application_id: str = "hairbrush_env") -> None:
        import rerun as rr

        self._rr = rr
        self._final = path
        self._ctx = atomic_path(path)
        self._tmp = self._ctx.__enter__()
        self._rec = rr.RecordingStream(application_id)
        self._rec.save(self._tmp)
        self._offset = 0.0  # episodes are laid end to end on the time axis

    def new_episode(self, episode: int, t_offset: float) -> None:
        self._offset = float(t_offset)
        self._rec.set_time("t", duration=self._offset)
        self._rec.log("episode", self._rr.TextLog(f"episode {episode} starts"))

    def _at(self, t: float) -> None:
        self._rec.set_time("t", duration=self._offset + float(t))

    def frame(
        self,
        t: float,
        strands: Sequence[np.ndarray],
        groups: Sequence[int],
        tines: np.ndarray,
        tine_radius: float,
    ) -> None:
        """Log the strands (coloured by their entwined group) and the brush's tines at sim time ``t``.

        ``tines`` are the bristle axis segments in the world, ``(n, 2, 3)``
        (:meth:`hairbrush_env.scene.BrushingSim.bristle_segments`), drawn at their own radius, so the recording
        shows whichever brush the scene was built with.
        """
        rr = self._rr
        self._at(t)
        colors = [rgb(PALETTE[g % len(PALETTE)]) for g in groups]
        self._rec.log(
            "scene/hair",
            rr.LineStrips3D([np.asarray(s, np.float32) for s in strands], colors=colors, radii=0.0008),
        )
        self._rec.log(
            "scene/brush",
            rr.LineStrips3D(np.asarray(tines, np.float32), colors=[(40, 40, 40)], radii=float(tine_radius)),
        )

    def force(self, t: float, value: float) -> None:
        self._at(t)
        self._rec.log("load_cell/force_N", self._rr.Scalars([float(value)]))

    def image(self, t: float, img: np.ndarray) -> None:
        self._at(t)
        # JPEG: a raw 320 × 240 frame is 230 kB, as much as ~30 frames of a 24-strand wig
        self._rec.log("camera/webcam", self._rr.Image(np.asarray(img)).compress(jpeg_quality=85))

    def stroke(self, t: float, index: int, max_force: float, entanglement: float) -> None:
        self._at(t)
        self._rec.log("strokes/max_force_N", self._rr.Scalars([float(max_force)]))
        self._rec.log("strokes/entanglement", self._rr.Scalars([float(entanglement)]))

    def close(self) -> None:
        if self._rec is None:
            return
        self._rec.flush()
        self._rec.disconnect()
        self._rec = None
        self._ctx.__exit__(None, None, None)


#: Codec of each video container OpenCV writes here. WebM/VP8 plays in every current browser (and encodes 6x faster
#: than VP9 here: 1.8 vs 11.4 s of CPU for 100 frames at 640x480); OpenCV's pip wheels
#: have no H.264 encoder, and their MP4 codec (``mp4v``, MPEG-4 Part 2) plays in video players but not browsers.
VIDEO_CODECS = {".webm": "VP80", ".mp4": "mp4v"}


class VideoWriter:
    """Video of webcam frames (OpenCV; WebM/VP8 or MP4/mp4v by the file's suffix), written atomically on
    :meth:`close`."""

    def __init__(self, path: str | os.PathLike[str], *, fps: float = 10.0) -> None:
        suffix = os.path.splitext(os.fspath(path))[1].lower()
        if suffix not in VIDEO_CODECS:
            raise ValueError(f"path: expected a {' or '.join(VIDEO_CODECS)} file, got {os.fspath(path)!r}")
        self._codec = VIDEO_CODECS[suffix]
        self._ctx = atomic_path(path)
        self._tmp = self._ctx.__enter__()
        self._fps = fps
        self._writer = None

    def add(self, img: np.ndarray) -> None:
        import cv2

        if self._writer is None:
            h, w = img.shape[:2]
            fourcc = cv2.VideoWriter_fourcc(*self._codec)
            self._writer = cv2.VideoWriter(str(self._tmp), fourcc, self._fps, (w, h))
        self._writer.write(cv2.cvtColor(np.ascontiguousarray(img), cv2.COLOR_RGB2BGR))

    def close(self) -> None:
        if self._writer is not None:
            self._writer.release()
            self._writer = None
        self._ctx.__exit__(None, None, None)


def plot_rollout(
    episodes: Sequence[Mapping], path: str | os.PathLike[str], *, force_threshold: float = PAIN_THRESHOLD_N
) -> None:
    """Force vs episode time (10 Hz samples), max force per stroke and entanglement per stroke, one colour per
    episode (does brushing detangle? stroke 0 is the pre-brushed wig).

    ``episodes`` are dicts as produced by :meth:`hairbrush_env.rollout.EpisodeLog.to_dict`.
    """
    fig, axes = new_figure(3, 1, width=5.5, height=4.0)
    ax_t, ax_s, ax_e = axes[0]
    for i, ep in enumerate(episodes):
        color = PALETTE[i % len(PALETTE)]
        t_all, f_all = [], []
        for step in ep["steps"]:
            t_all.extend(step["times"])
            f_all.extend(step["forces"])
            t_all.append(np.nan)  # break the line between strokes
            f_all.append(np.nan)
        label = f"{ep['policy']} · {ep['wig']} · ep {ep['episode']}"
        ax_t.plot(t_all, f_all, color=color, lw=1.2, label=label)
        # A stroke aborted at its first sample has no line to draw: mark it, or the largest force is not shown.
        lone = [(s["times"][0], s["forces"][0]) for s in ep["steps"] if len(s["forces"]) == 1]
        if lone:
            ax_t.plot(*zip(*lone, strict=True), "o", color=color, ms=4)
        ax_s.plot(
            np.arange(1, len(ep["steps"]) + 1),
            [s["max_force"] for s in ep["steps"]],
            "o-",
            color=color,
            label=label,
        )
        ax_e.plot(
            np.arange(0, len(ep["steps"]) + 1),
            [ep["entanglement_initial"], *(s["entanglement"] for s in ep["steps"])],
            "o-",
            color=color,
            label=label,
        )
    for ax in (ax_t, ax_s):
        ax.axhline(force_threshold, color="k", ls="--", lw=1, label="pain threshold F_T")
    ax_t.set(xlabel="brushing time [s]", ylabel="brushing force [N]", title="Load cell (10 Hz)")
    ax_s.set(xlabel="stroke", ylabel="max force [N]", title="Max force per stroke")
    ax_e.set(
        xlabel="stroke",
        ylabel="Σ|Lk|",
        title="Entanglement after each stroke (entwined + made)",
        ylim=(0, None),
    )
    ax_s.legend(fontsize=8)
    save_figure(fig, path)
