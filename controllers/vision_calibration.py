"""Validation of the vision curliness metric on rendered wigs, as thesis Fig. 3.4 (bottom).

For every wig preset, several pre-brushed states (seeds), small camera jitters, two hair colours and two lighting
levels are rendered from the fixed webcam and cropped to the hair (``BrushingSim.hair_window``, the rig's crop);
R_c (eq. 3.5) and the unclipped gradient ratio are computed on each image and compared with the true R/P. The
metric is useful for the sigmoid controller if it *ranks* the wigs like R/P (Spearman ρ) under every
colour/lighting condition. For side-on helices the unclipped ratio is 4 R/P (``controllers.vision``), so the
clipped R_c ties at 1 for every wig with R/P ≳ 1/4 and only the unclipped ratio can rank those.
``hairbrush vision calibrate`` regenerates the figure, the CSV and the JSON.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.stats import spearmanr

from hairbrush_env.constants import WEBCAM_SIZE

from .vision import gradient_ratio

#: Alternative appearance for the robustness check: blond hair (RGBA) vs the default dark brown.
BLOND = (0.85, 0.72, 0.45, 1.0)


@dataclass(frozen=True)
class Condition:
    name: str
    hair_rgba: tuple[float, float, float, float] | None  # None: the wig's own colour
    light_scale: float  # multiplies every light's diffuse colour


CONDITIONS = (
    Condition("default", None, 1.0),
    Condition("blond hair", BLOND, 1.0),
    Condition("dim light", None, 0.5),
)


def render_rows(
    presets: Sequence[str] | None = None,
    *,
    seeds: Sequence[int] = (0, 1),
    jitters: int = 2,
    jitter_m: float = 0.01,
    conditions: Sequence[Condition] = CONDITIONS,
    width: int = WEBCAM_SIZE[0],
    height: int = WEBCAM_SIZE[1],
    rng_seed: int = 0,
    progress: bool = False,
) -> list[dict]:
    """Render and measure; one row per (wig, seed, jitter, condition) with ``rc``, ``ratio`` and the true ``rp``.

    ``width`` × ``height`` is the webcam resolution: at 160×120 the tightest coils blur into tubes (docs/policies.md).
    """
    import mujoco
    from tqdm import tqdm

    from hairbrush_env.hair import PRESETS
    from hairbrush_env.scene import BrushingSim, SceneConfig

    names = list(PRESETS) if presets is None else list(presets)
    rng = np.random.default_rng(rng_seed)
    rows = []
    for name in tqdm(names, desc="wigs", disable=not progress):
        sim = BrushingSim(SceneConfig(wig=name, width=width, height=height))
        model = sim.model
        cam = model.camera("webcam").id
        cam_pos0 = model.cam_pos[cam].copy()
        light0 = model.light_diffuse.copy()
        rgba0 = model.flex_rgba.copy()
        try:
            for seed in seeds:
                sim.reset(seed)
                for j in range(jitters):
                    # the webcam is "fixed" but never placed twice exactly alike: jitter its position
                    model.cam_pos[cam] = cam_pos0 + (rng.uniform(-jitter_m, jitter_m, 3) if j else 0.0)
                    mujoco.mj_forward(model, sim.data)  # the renderer reads the camera pose from mjData
                    roi = sim.hair_window()
                    for cond in conditions:
                        model.light_diffuse[:] = light0 * cond.light_scale
                        model.flex_rgba[:] = rgba0 if cond.hair_rgba is None else np.asarray(cond.hair_rgba)
                        img = sim.render()
                        ratio = gradient_ratio(img, roi=roi)
                        rows.append(
                            {
                                "wig": name,
                                "rp": sim.curliness_true,
                                "seed": seed,
                                "jitter": j,
                                "condition": cond.name,
                                "rc": min(ratio, 1.0),
                                "ratio": ratio,
                            }
                        )
        finally:
            model.cam_pos[cam] = cam_pos0
            mujoco.mj_forward(model, sim.data)
            model.light_diffuse[:] = light0
            model.flex_rgba[:] = rgba0
            sim.close()
    return rows


def rank_correlation(rows: Sequence[dict], key: str = "rc") -> dict[str, float]:
    """Spearman ρ between the mean ``key`` (``rc`` or ``ratio``) per wig and R/P, per condition."""
    out = {}
    for cond in sorted({r["condition"] for r in rows}):
        sub = [r for r in rows if r["condition"] == cond]
        wigs = sorted({r["wig"] for r in sub}, key=lambda w: next(r["rp"] for r in sub if r["wig"] == w))
        rp = [next(r["rp"] for r in sub if r["wig"] == w) for w in wigs]
        values = [np.mean([r[key] for r in sub if r["wig"] == w]) for w in wigs]
        out[cond] = float(spearmanr(rp, values).statistic)
    return out


def rows_to_csv(rows: Sequence[dict]) -> str:
    buf = io.StringIO()
    writer = csv.DictWriter(
        buf, fieldnames=["wig", "rp", "seed", "jitter", "condition", "rc", "ratio"], lineterminator="\n"
    )
    writer.writeheader()
    writer.writerows(rows)
    return buf.getvalue()


def plot_calibration(rows: Sequence[dict], path: str | Path) -> None:
    """R_c (eq. 3.5) and the unclipped ratio versus true R/P (mean ± std over seeds and jitters), per condition.

    The dashed line is the thin-curve prediction 4 R/P for side-on helices; the dotted one R_c = R/P.
    """
    from hairbrush_env.viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(2, 1, width=5.25, height=4.5)
    for ax, key, label in (
        (axes[0, 0], "rc", "vision R_c (eq. 3.5, clipped)"),
        (axes[0, 1], "ratio", "Σ|G_y| / Σ|G_x| (unclipped)"),
    ):
        rho = rank_correlation(rows, key)
        for i, cond in enumerate(sorted(rho)):
            sub = [r for r in rows if r["condition"] == cond]
            rps = sorted({r["rp"] for r in sub})
            m = [np.mean([r[key] for r in sub if r["rp"] == rp]) for rp in rps]
            s = [np.std([r[key] for r in sub if r["rp"] == rp]) for rp in rps]
            ax.errorbar(
                rps, m, yerr=s, fmt="o-", capsize=3, color=PALETTE[i], label=f"{cond} (ρ = {rho[cond]:.2f})"
            )
        x = np.linspace(0.0, 0.85, 50)
        top = 1.0 if key == "rc" else 3.4
        ax.plot(x, np.minimum(4 * x, top), "k--", lw=1, label="side-on helix: 4 R/P")
        ax.plot([0, 0.85], [0, 0.85], "k:", lw=1, label="R/P")
        ax.set(xlabel="true curliness R/P", ylabel=label, xlim=(-0.05, 0.9), ylim=(0, top * 1.05))
        ax.legend(fontsize=8)
    axes[0, 0].set_title("Vision curliness on rendered wigs (thesis Fig. 3.4)")
    axes[0, 1].set_title("Before the clip: ranks curlier wigs too")
    save_figure(fig, path)
