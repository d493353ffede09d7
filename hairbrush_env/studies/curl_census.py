"""N-body interaction census of a simulated hair curl (thesis Figs 2.1c–d, 2.3a–b and 2.5).

Model (thesis chapter 2 appendix, "Hair curl interactions", and Fig. 2.10): ``n_hairs`` = 12 hairs of length
L0 = 0.2 m, radius r = 7.5e-5 m, E = 1 GPa, clamped at the top in a planar triangular lattice and hanging in the
same direction (−z). Every hair gets an independent random intrinsic curvature: the rest shape turns, at every
vertex, by κ δl about a random direction normal to the tangent, with κ ~ N(0, σ_κ²), σ_κ = ``curvature_std``
(1 /m in the thesis: a "relatively straight" curl, radius of curvature ~ length). The rods (same builder as
everything else, :mod:`hairbrush_env.rods`) start in their rest shape, are *jostled* — random horizontal forces on
every vertex for ``jostle_time`` — and then relax under gravity (gravity vs elasticity: l_g = (B/ρAg)^(1/3) ≈ 5 cm,
so the hairs straighten except near their free ends, as the thesis notes).

Census: :func:`hairbrush_env.topology.interaction_census` on the relaxed centerlines, 20 layers, three criteria:
``crossing`` (side view, projection on the x–z plane), ``contact`` (centerline distance < 2r·``contact_factor``)
and ``link`` (|Lk| of the pieces in a layer > 0.4, Fig. 2.5b). Results are averaged over seeds with standard errors.

The thesis picked 0.4 as "roughly the smallest linking threshold that provides nontrivial segregation of interaction
types" in its curls. In ours no layer pair reaches 0.4 (max 0.19 over 4 curls), so that criterion counts nothing.
The census therefore also reports ``link_auto``: the same rule applied to these curls
(:func:`~hairbrush_env.topology.empirical_lk_threshold`, one threshold for all seeds — the smallest at which no layer
has all hairs in one cluster), with the threshold in ``stats["lk_threshold_auto"]``.

Numerics: as in the thesis (mass ×1e8, gravity ÷1e8 there) mass is scaled up and gravity down, keeping m·g, the
statics, unchanged (``mass_scale``): MuJoCo's soft contacts are stiff per unit mass, and a 75 µm hair vertex of
2 mm weighs 5e-8 kg. Drag (``drag`` per unit length) removes the jostling energy before the census.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..executor import ExecutorConfig

__all__ = [
    "CRITERIA",
    "CurlSetup",
    "census_of",
    "plot_census",
    "run_census_sweep",
    "simulate_curl",
    "write_census",
]

CRITERIA = ("crossing", "contact", "link")

_SOLREF = (0.004, 1.0)
_SOLIMP = (0.99, 0.9999, 5e-6, 0.5, 2.0)


@dataclass(frozen=True)
class CurlSetup:
    """A curl of hairs (thesis Fig. 2.3, table Fig. 2.10).

    Parameters
    ----------
    n_hairs : int
        Hairs in the curl (12).
    length, radius, young, poisson, density : float
        L0 [m], r [m], E [Pa], ν (0.5 → 0.49 for MuJoCo), ρ [kg/m³].
    n_edges : int
        Edges per hair (100 = δl of 2 mm, Fig. 2.10).
    curvature_std : float
        σ of the Gaussian intrinsic curvature [1/m].
    spacing : float
        Clamp lattice spacing [m] (triangular lattice).
    jostle_force : float
        RMS random horizontal force per unit length during jostling [N/m], in units of the weight per length.
    jostle_time, settle_time : float
        Simulated seconds of jostling, then of relaxation.
    drag : float
        Viscous drag per unit length [N s/m²] (in scaled-mass units: multiplied by ``mass_scale`` internally).
    mass_scale : float
        Mass × this, gravity ÷ this (m·g constant).
    friction : float
        Hair–hair friction.
    contact_factor : float
        Contact criterion: centerline distance < 2 r × this.
    lk_threshold : float
        Link criterion threshold (0.4).
    n_layers : int
        Census layers (20).
    timestep : float
        Simulation step [s].
    """

    n_hairs: int = 12
    length: float = 0.2
    radius: float = 7.5e-5
    young: float = 1e9
    poisson: float = 0.49
    density: float = 1300.0
    n_edges: int = 100
    curvature_std: float = 1.0
    spacing: float = 4.0 * 7.5e-5
    jostle_force: float = 3.0
    jostle_time: float = 0.5
    settle_time: float = 1.5
    drag: float = 2e-4
    mass_scale: float = 1e3
    friction: float = 0.3
    contact_factor: float = 1.1
    lk_threshold: float = 0.4
    n_layers: int = 20
    timestep: float = 2e-3

    def __post_init__(self) -> None:
        for name in ("n_hairs", "n_edges", "n_layers"):
            v = getattr(self, name)
            if isinstance(v, bool) or int(v) != v or v < 2:
                raise ValueError(f"CurlSetup.{name} must be an integer >= 2, got {v!r}")
        for name in (
            "length",
            "radius",
            "young",
            "density",
            "spacing",
            "mass_scale",
            "timestep",
            "contact_factor",
        ):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"CurlSetup.{name} must be > 0, got {v!r}")
        for name in (
            "curvature_std",
            "jostle_force",
            "jostle_time",
            "settle_time",
            "drag",
            "friction",
            "lk_threshold",
        ):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"CurlSetup.{name} must be >= 0, got {v!r}")
        if not 0 <= self.poisson < 0.5:
            raise ValueError(f"CurlSetup.poisson must be in [0, 0.5), got {self.poisson!r}")


def _lattice(n: int, spacing: float) -> np.ndarray:
    """``n`` points of a planar triangular lattice (rows of a hexagon-ish patch), centred on the origin."""
    pts = []
    rows = math.ceil(math.sqrt(n)) + 1
    for i in range(-rows, rows + 1):
        for j in range(-rows, rows + 1):
            pts.append((spacing * (j + 0.5 * i), spacing * i * math.sqrt(3) / 2))
    pts_arr = np.array(pts)
    order = np.argsort(np.hypot(pts_arr[:, 0], pts_arr[:, 1]), kind="stable")
    chosen = pts_arr[order[:n]]
    return chosen - chosen.mean(axis=0)


def _random_rest_shape(root: np.ndarray, setup: CurlSetup, rng: np.random.Generator) -> np.ndarray:
    """A polyline hanging from ``root`` towards −z whose tangent turns by κ δl per vertex, κ ~ N(0, σ²)."""
    ds = setup.length / setup.n_edges
    t = np.array([0.0, 0.0, -1.0])
    pts = [np.asarray(root, dtype=float)]
    for _ in range(setup.n_edges):
        pts.append(pts[-1] + ds * t)
        kappa = rng.normal(0.0, setup.curvature_std)
        axis = rng.normal(size=3)
        axis -= axis.dot(t) * t
        axis /= np.linalg.norm(axis)
        ang = kappa * ds
        # Rodrigues rotation of the tangent about an axis normal to it
        t = t * math.cos(ang) + np.cross(axis, t) * math.sin(ang)
        t /= np.linalg.norm(t)
    return np.array(pts)


def simulate_curl(setup: CurlSetup, seed: int = 0) -> list[np.ndarray]:
    """Build, jostle and relax one curl; returns the hairs' centerlines (clamp first)."""
    import mujoco

    from ..rods import RodSpec, RodView, build_rod_model

    rng = np.random.default_rng(seed)
    roots = _lattice(setup.n_hairs, setup.spacing)
    condim = 1 if setup.friction == 0.0 else 3
    rods = [
        RodSpec(
            f"hair_{i}",
            _random_rest_shape(np.array([x, y, 0.0]), setup, rng),
            setup.radius,
            setup.young,
            poisson=setup.poisson,
            density=setup.density * setup.mass_scale,
            friction=setup.friction,
            condim=condim,
            contact_solref=_SOLREF,
            contact_solimp=_SOLIMP,
            kind="flex",  # the census is validated on DER flexes, and its drag acts on their vertex dofs
        )
        for i, (x, y) in enumerate(roots)
    ]
    model = build_rod_model(rods, timestep=setup.timestep, gravity=(0.0, 0.0, -9.81 / setup.mass_scale))
    data = mujoco.MjData(model)
    ds = setup.length / setup.n_edges
    dofs = []
    for rod in rods:
        for k in range(1, rod.n_edges + 1):
            dadr = model.jnt_dofadr[model.body_jntadr[model.body(f"{rod.name}_{k}").id]]
            dofs.append(range(dadr, dadr + 3))
    dof_idx = np.array([list(r) for r in dofs])  # (vertices, 3)
    # drag scales with the mass so the (overdamped) relaxation path is independent of mass_scale
    coef = setup.drag * setup.mass_scale * ds
    weight = rods[0].linear_density * (9.81 / setup.mass_scale) * ds  # weight per vertex (m·g is unscaled)
    n_jostle = round(setup.jostle_time / setup.timestep)
    n_settle = round(setup.settle_time / setup.timestep)
    kick = np.zeros((len(dof_idx), 3))
    for i in range(n_jostle + n_settle):
        if i < n_jostle and i % 25 == 0:  # a new random push every 50 ms
            kick = rng.normal(0.0, setup.jostle_force * weight, (len(dof_idx), 3))
            kick[:, 2] = 0.0
        data.qfrc_applied[:] = 0.0
        data.qfrc_applied[dof_idx] = -coef * data.qvel[dof_idx] + (kick if i < n_jostle else 0.0)
        mujoco.mj_step(model, data)
    mujoco.mj_forward(model, data)
    return [RodView(model, r.name).vertices(data) for r in rods]


def census_of(strands: Sequence[np.ndarray], setup: CurlSetup) -> dict[str, dict[int, float]]:
    """``{criterion: {N: ρ_N}}`` for the three criteria (interactions per metre of curl)."""
    return _census_and_link_matrices(strands, setup)[0]


def _census_and_link_matrices(strands: Sequence[np.ndarray], setup: CurlSetup):
    """The census and the layers' |Lk| matrices it was counted from (computed once, also for the threshold rule)."""
    from ..topology import interaction_census, layer_link_matrices, link_census_from_matrices

    out = {}
    for crit in ("crossing", "contact"):
        out[crit] = interaction_census(
            strands,
            n_layers=setup.n_layers,
            criterion=crit,
            contact_distance=2.0 * setup.radius * setup.contact_factor,
            axis=2,
        )
    mats, extent = layer_link_matrices(strands, n_layers=setup.n_layers, axis=2)
    out["link"] = link_census_from_matrices(mats, setup.lk_threshold, extent)
    return out, mats, extent


_POINT_VERSION = 2  # 2: results carry the layers' |Lk| matrices (older cache files are recomputed)


def run_point(point: dict[str, Any]) -> dict[str, Any]:
    """Sweep worker: ``{"setup": asdict(CurlSetup), "seed": int, "version": 2}`` → census (JSON keys are strings)
    plus ``"link_matrices"`` (layers × hairs × hairs |Lk|, NaN → None) and ``"extent"`` for the threshold rule."""
    setup = CurlSetup(**point["setup"])
    strands = simulate_curl(setup, seed=int(point["seed"]))
    cen, mats, extent = _census_and_link_matrices(strands, setup)
    out: dict[str, Any] = {crit: {str(n): v for n, v in c.items()} for crit, c in cen.items()}
    out["link_matrices"] = np.where(np.isnan(mats), None, mats).tolist()
    out["extent"] = extent
    return out


def _table(rows: list[dict[str, float]]) -> dict[str, list]:
    """Mean and standard error over seeds of ``{N: ρ_N}`` dicts (missing N count as 0)."""
    n_max = max((int(n) for r in rows for n in r), default=2)
    ns = list(range(2, n_max + 1))
    table = np.array([[r.get(str(n), 0.0) for n in ns] for r in rows])  # (seeds, N)
    sem = table.std(axis=0, ddof=1) / math.sqrt(len(rows)) if len(rows) > 1 else np.zeros(len(ns))
    return {"N": ns, "mean": table.mean(axis=0).tolist(), "sem": sem.tolist(), "per_seed": table.tolist()}


def run_census_sweep(
    setup: CurlSetup,
    seeds: Iterable[int],
    *,
    cache_dir,
    executor: ExecutorConfig | None = None,
    progress: bool = True,
) -> dict[str, Any]:
    """Census over several seeds (cached, resumable via :mod:`.sweep`, run by ``executor``: this process, local
    workers or Ray); mean and standard error of ρ_N."""
    from ..topology import empirical_lk_threshold, link_census_from_matrices
    from .sweep import run_sweep

    seeds = list(seeds)
    if not seeds:
        raise ValueError("seeds must not be empty")
    points = [{"setup": asdict(setup), "seed": int(s), "version": _POINT_VERSION} for s in seeds]
    raw = run_sweep(run_point, points, cache_dir, executor=executor, desc="census", progress=progress)
    stats: dict[str, Any] = {"setup": asdict(setup), "seeds": seeds, "criteria": {}}
    for crit in CRITERIA:
        stats["criteria"][crit] = _table([r[crit] for r in raw])
    mats = [np.array(r["link_matrices"], dtype=float) for r in raw]  # None → NaN
    auto = empirical_lk_threshold(np.concatenate(mats))
    auto_rows = [
        {str(n): v for n, v in link_census_from_matrices(m, auto, r["extent"]).items()}
        for m, r in zip(mats, raw, strict=True)
    ]
    stats["criteria"]["link_auto"] = _table(auto_rows)
    stats["lk_threshold_auto"] = auto
    finite = np.concatenate([m[np.isfinite(m) & (m > 0)] for m in mats])
    stats["layer_lk_quantiles"] = {
        q: float(np.percentile(finite, float(q))) if finite.size else 0.0 for q in ("50", "90", "99", "100")
    }
    return stats


def write_census(stats: dict[str, Any], out_dir) -> list:
    """``census.csv`` (criterion, N, mean ρ, sem) and ``census.json``."""
    from pathlib import Path

    from ..io import write_json, write_text

    out = Path(out_dir)
    lines = ["criterion,N,rho_mean_per_m,rho_sem_per_m"]
    for crit, t in stats["criteria"].items():
        lines += [f"{crit},{n},{m:.6g},{e:.6g}" for n, m, e in zip(t["N"], t["mean"], t["sem"], strict=True)]
    return [write_text(out / "census.csv", "\n".join(lines) + "\n"), write_json(out / "census.json", stats)]


def _label(crit: str, stats: dict[str, Any]) -> str:
    if crit == "link":
        return f"link |Lk| > {stats['setup']['lk_threshold']:g}"
    if crit == "link_auto":
        return f"link |Lk| > {stats['lk_threshold_auto']:.3f} (thesis rule)"
    return crit


def plot_census(stats: dict[str, Any], path) -> None:
    """Bar chart of ρ_N per criterion with standard-error bars (thesis Figs 2.3b, 2.5)."""
    from ..viz import PALETTE, new_figure, save_figure

    fig, axes = new_figure(1, 1, width=6.0, height=4.0)
    ax = axes[0, 0]
    crits = list(stats["criteria"])
    width = 0.8 / len(crits)
    for i, crit in enumerate(crits):
        t = stats["criteria"][crit]
        ns = np.asarray(t["N"], dtype=float)
        ax.bar(ns + (i - (len(crits) - 1) / 2) * width, t["mean"], width, yerr=t["sem"], capsize=3,
               color=PALETTE[i], label=_label(crit, stats))  # fmt: skip
    n_hairs, n_curls = stats["setup"]["n_hairs"], len(stats["seeds"])
    ax.set(xlabel="N (hairs per interaction)", ylabel="ρ [interactions / m]",
           title=f"N-body interactions, {n_hairs} hairs, {n_curls} curls (±s.e.)")  # fmt: skip
    ax.legend()
    save_figure(fig, path)
