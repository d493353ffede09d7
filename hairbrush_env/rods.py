"""Hair strands as discrete elastic rods (DER) in MuJoCo 4.0.

MuJoCo 4.0 removed ``<composite>`` and the cable plugin; a rod is now a 1D flex (``dim=1``) with
``<elasticity young=... poisson=... shear=...>`` (DER bending + torsion, per-edge twist hinge joints) plus an edge
equality constraint for inextensibility. This module builds such rods directly through :class:`mujoco.MjSpec`
(``spec.add_flex`` + vertex bodies + twist bodies + an ``mjEQ_FLEX`` equality) instead of the ``<flexcomp>`` XML
macro, because

* ``MjsBody.make_flex`` (the MjSpec flexcomp) cannot take explicit points or pins, and XML snippets would have to be
  re-attached into the scene spec;
* we need per-vertex masses (see *mass lumping*), which ``flexcomp mass=`` cannot express;
* the same :func:`add_rod` then works on any spec and any parent body.

The raw flex built here is bit-identical to what ``<flexcomp type="direct" dim="1">`` expands into when given the same
masses (checked in ``tests/test_rods.py::test_matches_flexcomp_expansion``): vertex bodies ``<name>_<k>`` with three
world-aligned slide joints, twist bodies/hinges ``<name>_twist_<e>`` ... ``<name>_twist`` under the world body (their
names bind them to the flex edges, so they must follow that scheme), and twist-body polar inertia ``m_e r² / 2``.

Design decisions and the evidence behind them (0.2 m cantilever, r = 1 mm, E = 10 GPa, ρ = 1300 kg/m³, measured with
MuJoCo 4.0.1, see ``scripts/benchmark_sim.py``):

Integrator ``discrete`` + solver ``Newton``
    1D rod elasticity is rejected by ``implicit``/``implicitfast``; ``discrete`` integrates it implicitly in position
    and is stable at large steps (static deflection identical to 4 digits from dt = 1 ms to 32 ms). Newton needs 0–1
    iterations per step here; CG was reported by the team to stop at its iteration cap with wrong statics.
Edge equality ``solref = (1e-4, 1)``
    The default edge equality (``solref = 0.02``) is soft: at 100 edges the cantilever stretched by 4.6 % and deflected
    +10.6 % too much. With ``1e-4`` the length error is 1e-6 (100 edges) and ≤ 1e-4 in a 970-dof helix.
``refsafe`` left ENABLED
    Under ``discrete`` the flag does not touch equality rows (documented for the flag; we checked that disabling it
    changes the cantilever results by exactly 0.0 at dt = 2 ms and 8 ms), while it still protects contact and limit rows
    of the scene whose ``solref`` the step cannot resolve. The team's "disable refsafe" advice predates ``discrete``.
Clamp through a short ghost edge
    A clamp pins both points of the first flex edge to the parent. DER places the slope of an edge at its midpoint, so
    pinning the real first edge clamps the rod at ``points[0] + ℓ/2``: the cantilever was 2/n too stiff (-19.0 % at 10
    edges, -2.0 % at 100). We therefore prepend a pinned ghost vertex at ``points[0] - GHOST_FRACTION·(points[1] -
    points[0])``; the clamp is then (up to 0.5 % of one edge) at ``points[0]`` with the tangent of the first segment,
    and convergence becomes second order (+1.2 % at 10 edges, +0.35 % at 20, +0.08 % at 50). ``points[0]`` is pinned,
    ``points[1]`` onwards move. :class:`RodView` hides the ghost vertex.
Consistent mass lumping
    ``flexcomp mass=`` gives every point ``M/(n+1)``, so the free tip carries a double share. We give point ``k`` the
    mass ``ρA(ℓ_{k-1} + ℓ_k)/2`` (ends get half shares), which is what the ``wL⁴/8EI`` comparison assumes.
Default discretization: 20 edges per strand (:data:`DEFAULT_N_EDGES`)
    Gravity cantilever +0.35 %, end-loaded cantilever +0.20 %. Curved rods need finer edges: a helical spring's axial
    stiffness is +32 % / +7.7 % / +3.5 % / +2.0 % / -0.1 % off at 10 / 20 / 30 / 40 / 80 edges per turn, i.e. keep
    ≤ ~12° of turning per edge (≥ 30 edges per curl turn) for < 5 % stiffness error.
Timestep 2 ms (:data:`DEFAULT_TIMESTEP`)
    Statics do not depend on it (above). Dynamics: the first cantilever mode (19.4 Hz) is simulated at 18.9 Hz
    (-2.6 %); the implicit step damps it numerically (amplitude ×0.23 per 0.1 s; ×0.48 at 1 ms, ×0.05 at 4 ms).

Reading positions: flex vertex positions are ``data.flexvert_xpos`` (valid after ``mj_forward``/``mj_step``), see
:class:`RodView`. Rod reference frames live in ``data.plastic``; save/restore with
``mjtState.mjSTATE_INTEGRATION`` (which includes ``mjSTATE_PLASTIC``) or resets are not exact.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Literal

import mujoco
import numpy as np

__all__ = [
    "DEFAULT_N_EDGES",
    "DEFAULT_TIMESTEP",
    "EDGE_SOLREF",
    "GHOST_FRACTION",
    "RodSpec",
    "RodView",
    "StudyResult",
    "add_rod",
    "bending_stiffness",
    "build_rod_model",
    "cantilever_study",
    "configure_rod_options",
    "helix_study",
    "polyline_length",
    "resample_polyline",
    "rod_length",
    "rod_vertices",
    "shear_modulus",
    "straight_rod_points",
    "twisting_stiffness",
]

DEFAULT_TIMESTEP = 2e-3
"""Simulation step [s]; statics are step-independent up to 32 ms, dynamics keep the first mode within 3 %."""

DEFAULT_N_EDGES = 20
"""Edges per (straight) strand; cantilever deflection within 0.4 % of Euler–Bernoulli."""

EDGE_SOLREF = (1e-4, 1.0)
"""Edge-equality ``solref``: stiff enough for < 1e-4 relative stretch (the MuJoCo default 0.02 stretched 4.6 %)."""

GHOST_FRACTION = 0.01
"""Length of the pinned ghost edge behind a clamped root, as a fraction of the first edge (see module docstring)."""

_TWIST_BODY_MASS = 1e-9  # what flexcomp uses: the twist bodies only carry the polar inertia of their edge
# MuJoCo refuses moving bodies whose mass or inertia is below mjMINVAL (1e-15). A 40 µm hair edge of 1 cm has a polar
# inertia of ~5e-17 kg m², so twist inertias are floored here; this overestimates the rolling inertia of very thin
# hair (irrelevant for statics, and the twist dof is integrated implicitly, so stability is unaffected).
_MIN_INERTIA = 4.0 * mujoco.mjMINVAL
_FRICTION_TORSION_ROLL = (0.005, 0.0001)  # MuJoCo defaults for the torsional / rolling friction coefficients


# --------------------------------------------------------------------------------------------- material helpers
def shear_modulus(young: float, poisson: float) -> float:
    """Isotropic shear modulus ``G = E / (2 (1 + ν))`` [Pa]."""
    return young / (2.0 * (1.0 + poisson))


def bending_stiffness(young: float, radius: float) -> float:
    """Bending stiffness ``E I`` of a circular section, ``I = π r⁴ / 4`` [N m²]."""
    return young * math.pi * radius**4 / 4.0


def twisting_stiffness(shear: float, radius: float) -> float:
    """Torsional stiffness ``G J`` of a circular section, ``J = π r⁴ / 2`` [N m²]."""
    return shear * math.pi * radius**4 / 2.0


# ----------------------------------------------------------------------------------------------- polylines
def polyline_length(points: np.ndarray) -> float:
    """Total length of a polyline given as an ``(n, 3)`` array."""
    p = np.asarray(points, dtype=float)
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def straight_rod_points(
    start: Sequence[float],
    direction: Sequence[float],
    length: float,
    n_edges: int = DEFAULT_N_EDGES,
) -> np.ndarray:
    """Evenly spaced points of a straight rod.

    Parameters
    ----------
    start : sequence of float
        Root point.
    direction : sequence of float
        Direction of the rod (normalized internally).
    length : float
        Rod length.
    n_edges : int
        Number of edges (``n_edges + 1`` points).

    Returns
    -------
    np.ndarray
        ``(n_edges + 1, 3)`` points.
    """
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    s = np.linspace(0.0, length, n_edges + 1)
    return np.asarray(start, dtype=float)[None, :] + s[:, None] * d[None, :]


def resample_polyline(points: np.ndarray, n_edges: int = DEFAULT_N_EDGES) -> np.ndarray:
    """Resample a polyline to ``n_edges`` edges of equal arc length (linear interpolation).

    Parameters
    ----------
    points : np.ndarray
        ``(m, 3)`` polyline.
    n_edges : int
        Number of edges of the result.

    Returns
    -------
    np.ndarray
        ``(n_edges + 1, 3)`` points; first and last point are kept.
    """
    p = np.asarray(points, dtype=float)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], n_edges + 1)
    return np.stack([np.interp(t, s, p[:, k]) for k in range(3)], axis=1)


# --------------------------------------------------------------------------------------------------- spec
def _check_finite(name: str, value: float, *, positive: bool = False, nonneg: bool = False) -> None:
    if not math.isfinite(value):
        raise ValueError(f"RodSpec.{name} must be finite, got {value!r}")
    if positive and value <= 0.0:
        raise ValueError(f"RodSpec.{name} must be > 0, got {value!r}")
    if nonneg and value < 0.0:
        raise ValueError(f"RodSpec.{name} must be >= 0, got {value!r}")


@dataclass(frozen=True)
class RodSpec:
    """Geometry and material of one rod (hair strand).

    Parameters
    ----------
    name : str
        Flex name; also the prefix of the generated bodies (``<name>_<k>`` for ``points[k]``) and twist joints.
    points : np.ndarray
        ``(n, 3)`` centerline in the frame of the parent body. This is also the rest shape (curls stay curled).
    radius : float
        Cross-section radius [m]; used for stiffness, mass, collision and rendering.
    young : float
        Young's modulus [Pa].
    shear : float or None
        Shear modulus [Pa] for torsion; ``None`` means isotropic ``E / (2 (1 + poisson))``.
    poisson : float
        Poisson's ratio, in ``[0, 0.5)`` (MuJoCo rejects 0.5).
    density : float
        Mass density [kg/m³] (hair keratin ≈ 1300).
    damping : float
        Rayleigh damping of bending/torsion [s] (MuJoCo ``elasticity damping``).
    clamp : {"start", None}
        ``"start"``: the root is built in to the parent body at ``points[0]`` with tangent ``points[1] - points[0]``
        (all points but ``points[0]`` move). ``None``: free rod.
    friction : float
        Sliding friction coefficient of the rod's contacts.
    rgba : tuple of float
        Colour.
    contype, conaffinity : int
        Contact bitmasks (as for geoms).
    condim : int
        Contact dimensionality (1: frictionless, 3: sliding friction, 4: + torsional, 6: + rolling).
    group : int
        Visualisation group.
    selfcollide : bool
        Let elements of the same rod collide with each other (off by default: costly, rarely needed for hair).
    margin : float
        Contact margin [m].
    contact_solref, contact_solimp : tuple of float, optional
        Contact ``solref`` / ``solimp`` of the flex (``None``: MuJoCo defaults ``(0.02, 1)`` /
        ``(0.9, 0.95, 0.001, 0.5, 2)``, whose 1 mm impedance width lets a rod sink ~1 mm into a capsule — more than a
        hair's radius; for thin hair use e.g. ``(0.004, 1)`` and ``(0.95, 0.99, 1e-4, 0.5, 2)``).
    edge_solref : tuple of float
        ``solref`` of the inextensibility constraint (keep the default unless you measured otherwise).
    """

    name: str
    points: np.ndarray
    radius: float
    young: float
    shear: float | None = None
    poisson: float = 0.49
    density: float = 1300.0
    damping: float = 0.0
    clamp: Literal["start"] | None = "start"
    friction: float = 0.3
    rgba: tuple[float, float, float, float] = (0.35, 0.22, 0.12, 1.0)
    contype: int = 1
    conaffinity: int = 1
    condim: int = 3
    group: int = 0
    selfcollide: bool = False
    margin: float = 0.0
    contact_solref: tuple[float, float] | None = None
    contact_solimp: tuple[float, float, float, float, float] | None = None
    edge_solref: tuple[float, float] = EDGE_SOLREF

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValueError(f"RodSpec.name must be a non-empty string, got {self.name!r}")
        try:
            pts = np.array(
                self.points, dtype=float
            )  # a private copy, so freezing it cannot affect the caller
        except (TypeError, ValueError) as exc:
            raise ValueError(f"RodSpec.points must be an (n, 3) float array: {exc}") from exc
        if pts.ndim != 2 or pts.shape[1] != 3 or pts.shape[0] < 2:
            raise ValueError(f"RodSpec.points must have shape (n>=2, 3), got {pts.shape}")
        if not np.all(np.isfinite(pts)):
            raise ValueError("RodSpec.points must be finite")
        seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        if np.any(seg <= 1e-12 * max(1.0, float(np.abs(pts).max()))):
            raise ValueError(
                f"RodSpec.points has zero-length segments at indices {np.flatnonzero(seg <= 1e-12)}"
            )
        if self.clamp not in ("start", None):
            raise ValueError(f"RodSpec.clamp must be 'start' or None, got {self.clamp!r}")
        if self.clamp == "start" and pts.shape[0] < 3:
            raise ValueError("RodSpec.points: a clamped rod needs at least 3 points (2 edges)")
        pts.setflags(write=False)
        object.__setattr__(self, "points", pts)
        _check_finite("radius", self.radius, positive=True)
        _check_finite("young", self.young, positive=True)
        _check_finite("density", self.density, positive=True)
        _check_finite("damping", self.damping, nonneg=True)
        _check_finite("friction", self.friction, nonneg=True)
        _check_finite("margin", self.margin, nonneg=True)
        _check_finite("poisson", self.poisson, nonneg=True)
        if self.poisson >= 0.5:
            raise ValueError(f"RodSpec.poisson must be in [0, 0.5), got {self.poisson!r}")
        if self.shear is not None:
            _check_finite("shear", self.shear, positive=True)
        if self.condim not in (1, 3, 4, 6):
            raise ValueError(f"RodSpec.condim must be 1, 3, 4 or 6, got {self.condim!r}")
        if len(self.rgba) != 4:
            raise ValueError(f"RodSpec.rgba must have 4 entries, got {self.rgba!r}")
        if self.contact_solref is not None and len(self.contact_solref) != 2:
            raise ValueError(f"RodSpec.contact_solref must have 2 entries, got {self.contact_solref!r}")
        if self.contact_solimp is not None and len(self.contact_solimp) != 5:
            raise ValueError(f"RodSpec.contact_solimp must have 5 entries, got {self.contact_solimp!r}")
        if len(self.edge_solref) != 2 or not all(math.isfinite(v) for v in self.edge_solref):
            raise ValueError(f"RodSpec.edge_solref must be 2 finite numbers, got {self.edge_solref!r}")

    @property
    def n_edges(self) -> int:
        """Number of edges of the given centerline."""
        return int(self.points.shape[0] - 1)

    @property
    def length(self) -> float:
        """Rest length [m]."""
        return polyline_length(self.points)

    @property
    def linear_density(self) -> float:
        """Mass per unit length ``ρ π r²`` [kg/m]."""
        return self.density * math.pi * self.radius**2

    @property
    def bending_stiffness(self) -> float:
        """``E I`` [N m²]."""
        return bending_stiffness(self.young, self.radius)

    @property
    def shear_modulus(self) -> float:
        """Shear modulus actually used for torsion [Pa]."""
        return shear_modulus(self.young, self.poisson) if self.shear is None else self.shear

    @property
    def twisting_stiffness(self) -> float:
        """``G J`` [N m²]."""
        return twisting_stiffness(self.shear_modulus, self.radius)


# --------------------------------------------------------------------------------------------- building
def _resolve_body(spec: mujoco.MjSpec, parent: mujoco.MjsBody | str | None) -> mujoco.MjsBody:
    if parent is None:
        return spec.worldbody
    if isinstance(parent, str):
        body = spec.body(parent)
        if body is None:
            raise ValueError(f"parent body {parent!r} not found in spec")
        return body
    return parent


def add_rod(
    spec: mujoco.MjSpec,
    rod: RodSpec,
    *,
    parent: mujoco.MjsBody | str | None = None,
) -> mujoco.MjsFlex:
    """Add one rod to ``spec`` as a raw 1D flex with DER elasticity.

    Creates (``k`` indexes ``rod.points``)

    * bodies ``<name>_<k>`` (children of ``parent``, placed at ``points[k]``) with three slide joints and the
      consistently lumped mass ``ρA(ℓ_{k-1} + ℓ_k)/2`` — for every moving point (``k ≥ 1`` if clamped);
    * twist bodies + hinge joints ``<name>_twist_<e>`` / ``<name>_twist`` under the world body (names fixed by
      MuJoCo; ``e`` counts flex edges, which include the ghost edge of a clamped rod);
    * the flex ``<name>`` (no self-collision unless ``rod.selfcollide``) and its edge equality constraint.

    Parameters
    ----------
    spec : mujoco.MjSpec
        Any spec; call :func:`configure_rod_options` on it as well (rods require the ``discrete`` integrator).
    rod : RodSpec
        The rod; ``rod.points`` are expressed in the frame of ``parent``.
    parent : mujoco.MjsBody or str or None
        Body holding the clamped root (and the parent of the vertex bodies); ``None`` = world. A moving parent
        (with joints) receives the rod's reaction force and torque. Unclamped rods need a jointless parent.

    Returns
    -------
    mujoco.MjsFlex
        The flex (its properties may still be edited before compiling).
    """
    pbody = _resolve_body(spec, parent)
    pname = pbody.name or "world"
    given = rod.points
    clamped = rod.clamp == "start"
    if clamped:
        # Pinned ghost vertex just behind the root: with the first *flex* edge that short, DER's built-in end sits at
        # points[0] instead of half an edge further out (see module docstring: -2/n error -> second order).
        ghost = given[0] - GHOST_FRACTION * (given[1] - given[0])
        pts = np.vstack([ghost, given])
    else:
        pts = np.asarray(given)
    offset = len(pts) - len(given)  # flex vertex index = point index + offset
    n_flex_edges = len(pts) - 1

    seg_given = np.linalg.norm(np.diff(given, axis=0), axis=1)
    lam = rod.linear_density
    point_mass = np.zeros(len(given))
    point_mass[:-1] += 0.5 * lam * seg_given
    point_mass[1:] += 0.5 * lam * seg_given

    vertbody: list[str] = []
    vert: list[float] = []
    for i, p in enumerate(pts):
        k = i - offset
        if clamped and k <= 0:  # ghost and root: part of the parent body
            vertbody.append(pname)
            vert.extend(float(c) for c in p)
            continue
        body = pbody.add_body(name=f"{rod.name}_{k}", pos=[float(c) for c in p])
        body.explicitinertial = True
        body.ipos = [0.0, 0.0, 0.0]  # unset ipos would not default to the body origin
        body.mass = float(point_mass[k])
        # A point mass: rotational inertia never enters (slide joints only) but must be positive. Same formula
        # as flexcomp (inertia box of 1 cm), floored for MuJoCo's mjMINVAL check.
        body.inertia = [max(float(point_mass[k]) * 1e-4 / 6.0, _MIN_INERTIA)] * 3
        for axis in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)):
            body.add_joint(type=mujoco.mjtJoint.mjJNT_SLIDE, axis=list(axis))
        vertbody.append(f"{rod.name}_{k}")
        vert.extend([0.0, 0.0, 0.0])

    if n_flex_edges >= 2:
        seg_flex = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        first = 1 if clamped else 0  # a clamped first edge has no twist dof
        for e in range(first, n_flex_edges):
            jname = f"{rod.name}_twist" if e == n_flex_edges - 1 else f"{rod.name}_twist_{e}"
            tbody = spec.worldbody.add_body(name=jname)
            tbody.explicitinertial = True
            tbody.ipos = [0.0, 0.0, 0.0]
            tbody.mass = _TWIST_BODY_MASS
            polar = 0.5 * lam * float(seg_flex[e]) * rod.radius**2  # polar inertia m_e r²/2 of the edge
            tbody.inertia = [max(polar, _MIN_INERTIA)] * 3
            tbody.add_joint(name=jname, type=mujoco.mjtJoint.mjJNT_HINGE, axis=[1.0, 0.0, 0.0])

    contact_kwargs: dict[str, list[float]] = {}
    if rod.contact_solref is not None:
        contact_kwargs["solref"] = [float(v) for v in rod.contact_solref]
    if rod.contact_solimp is not None:
        contact_kwargs["solimp"] = [float(v) for v in rod.contact_solimp]
    flex = spec.add_flex(
        name=rod.name,
        dim=1,
        radius=rod.radius,
        vertbody=vertbody,
        vert=vert,
        elem=[v for e in range(n_flex_edges) for v in (e, e + 1)],
        young=rod.young,
        poisson=rod.poisson,
        shear=0.0 if rod.shear is None else rod.shear,  # 0 means "isotropic from young/poisson" in MuJoCo
        damping=rod.damping,
        friction=[rod.friction, *_FRICTION_TORSION_ROLL],
        rgba=list(rod.rgba),
        contype=rod.contype,
        conaffinity=rod.conaffinity,
        condim=rod.condim,
        group=rod.group,
        margin=rod.margin,
        selfcollide=mujoco.mjtFlexSelf.mjFLEXSELF_AUTO
        if rod.selfcollide
        else mujoco.mjtFlexSelf.mjFLEXSELF_NONE,
        **contact_kwargs,
    )
    spec.add_equality(type=mujoco.mjtEq.mjEQ_FLEX, name1=rod.name, solref=list(rod.edge_solref))
    return flex


def configure_rod_options(spec: mujoco.MjSpec, *, timestep: float = DEFAULT_TIMESTEP) -> None:
    """Set the global options DER rods need.

    * ``integrator = discrete``: the only integrator that treats rod elasticity implicitly (``implicit`` /
      ``implicitfast`` reject it, ``Euler`` needs sub-millisecond steps); statics are step-independent to 32 ms.
    * ``solver = Newton``: 0–1 iterations per step on rods; CG hit its iteration cap with wrong statics (team) and
      PGS does not support flex.
    * ``refsafe`` is deliberately left as is (enabled by default): under ``discrete`` it does not clamp equality
      rows — toggling it changed the rod results by exactly zero — but it keeps too-stiff contacts stable.

    Parameters
    ----------
    spec : mujoco.MjSpec
        Spec to modify in place.
    timestep : float
        Simulation step [s].
    """
    if not (math.isfinite(timestep) and timestep > 0):
        raise ValueError(f"timestep must be > 0, got {timestep!r}")
    spec.option.timestep = timestep
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_DISCRETE
    spec.option.solver = mujoco.mjtSolver.mjSOL_NEWTON


def build_rod_model(
    rods: Sequence[RodSpec],
    *,
    timestep: float = DEFAULT_TIMESTEP,
    gravity: Sequence[float] = (0.0, 0.0, -9.81),
    extra: Callable[[mujoco.MjSpec], None] | None = None,
) -> mujoco.MjModel:
    """Compile a bare model containing only ``rods`` (clamped to the world), for studies and tests.

    Parameters
    ----------
    rods : sequence of RodSpec
        Rods to add (names must be unique).
    timestep : float
        Simulation step [s].
    gravity : sequence of float
        Gravity vector [m/s²].
    extra : callable, optional
        ``extra(spec)`` is called after the rods are added and before compiling (add obstacles, loads, ...).

    Returns
    -------
    mujoco.MjModel
    """
    spec = mujoco.MjSpec()
    spec.modelname = "rods"
    configure_rod_options(spec, timestep=timestep)
    spec.option.gravity = [float(g) for g in gravity]
    for rod in rods:
        add_rod(spec, rod)
    if extra is not None:
        extra(spec)
    return spec.compile()


# ---------------------------------------------------------------------------------------------- reading
class RodView:
    """Cached index lookup for one rod of a compiled model.

    Parameters
    ----------
    model : mujoco.MjModel
        Compiled model containing a rod built by :func:`add_rod`.
    name : str
        Rod (flex) name.

    Notes
    -----
    Positions come from ``data.flexvert_xpos``, which MuJoCo fills in ``mj_forward``/``mj_step`` (call
    ``mj_forward`` after ``MjData`` creation or ``mj_setState`` before reading). The pinned ghost vertex of a
    clamped rod is skipped, so row ``k`` of :meth:`vertices` is ``points[k]`` of the :class:`RodSpec`.
    """

    def __init__(self, model: mujoco.MjModel, name: str) -> None:
        fid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_FLEX, name)
        if fid < 0:
            raise KeyError(f"no rod (flex) named {name!r}")
        if model.flex_dim[fid] != 1:
            raise ValueError(f"flex {name!r} is not a rod (dim={model.flex_dim[fid]})")
        self.name = name
        self.flex_id = int(fid)
        adr = int(model.flex_vertadr[fid])
        num = int(model.flex_vertnum[fid])
        # add_rod's clamped rods start with ghost + root, both on the parent body; the ghost edge is the only
        # edge that short (GHOST_FRACTION of its neighbour), which tells it apart from a rod pinned by flexcomp.
        bodies = model.flex_vertbodyid[adr : adr + num]
        eadr = int(model.flex_edgeadr[fid])
        lengths = model.flexedge_length0[eadr : eadr + int(model.flex_edgenum[fid])]
        self.has_ghost = bool(
            num >= 3 and bodies[0] == bodies[1] and lengths[0] < 2.0 * GHOST_FRACTION * lengths[1]
        )
        start = adr + (1 if self.has_ghost else 0)
        self._rows = slice(start, adr + num)
        self.n_points = adr + num - start

    def vertices(self, data: mujoco.MjData) -> np.ndarray:
        """Current centerline, an ``(n, 3)`` copy in world coordinates."""
        return data.flexvert_xpos[self._rows].copy()

    def length(self, data: mujoco.MjData) -> float:
        """Current centerline length [m]."""
        return polyline_length(data.flexvert_xpos[self._rows])


def rod_vertices(model: mujoco.MjModel, data: mujoco.MjData, name: str) -> np.ndarray:
    """Current centerline of rod ``name`` as an ``(n, 3)`` array (see :class:`RodView`; cache one in loops)."""
    return RodView(model, name).vertices(data)


def rod_length(model: mujoco.MjModel, data: mujoco.MjData, name: str) -> float:
    """Current centerline length of rod ``name`` [m]."""
    return RodView(model, name).length(data)


# ------------------------------------------------------------------------------------------ validation studies
@dataclass(frozen=True)
class StudyResult:
    """Outcome of a static validation study (see :func:`cantilever_study`, :func:`helix_study`).

    Attributes
    ----------
    n_edges : int
        Edges of the simulated rod.
    measured, expected : float
        Simulated and analytic quantity (tip deflection [m] or spring stiffness [N/m]).
    rel_error : float
        ``measured / expected - 1``.
    length_error : float
        Relative change of the centerline length at the end of the run.
    steps_per_second : float
        Wall-clock simulation speed of the run (single thread).
    """

    n_edges: int
    measured: float
    expected: float
    rel_error: float
    length_error: float
    steps_per_second: float


def _run_timed(model: mujoco.MjModel, data: mujoco.MjData, seconds: float) -> float:
    import time  # local: only the studies need wall-clock timing

    steps = max(1, round(seconds / model.opt.timestep))
    t0 = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(model, data)
    return steps / (time.perf_counter() - t0)


def cantilever_study(
    n_edges: int,
    *,
    load: Literal["gravity", "tip"] = "gravity",
    length: float = 0.2,
    radius: float = 1e-3,
    young: float = 10e9,
    density: float = 1300.0,
    tip_force: float = 3e-3,
    timestep: float = DEFAULT_TIMESTEP,
    settle: float = 1.5,
) -> StudyResult:
    """Static tip deflection of a clamped straight rod vs Euler–Bernoulli.

    ``load="gravity"``: ``w L⁴ / (8 E I)`` with ``w = ρ g π r²``; ``load="tip"``: force ``tip_force`` at the free end
    (gravity off), ``F L³ / (3 E I)``. The defaults give 1.0 mm = 0.5 % of ``L`` (small-deflection regime).
    """
    g = 9.81
    rod = RodSpec(
        name="cantilever",
        points=straight_rod_points([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], length, n_edges),
        radius=radius,
        young=young,
        density=density,
    )
    gravity = (0.0, 0.0, -g) if load == "gravity" else (0.0, 0.0, 0.0)
    model = build_rod_model([rod], timestep=timestep, gravity=gravity)
    data = mujoco.MjData(model)
    ei = bending_stiffness(young, radius)
    if load == "gravity":
        expected = rod.linear_density * g * length**4 / (8.0 * ei)
    else:
        expected = tip_force * length**3 / (3.0 * ei)
        data.xfrc_applied[model.body(f"cantilever_{n_edges}").id, 2] = -tip_force
    sps = _run_timed(model, data, settle)
    view = RodView(model, "cantilever")
    measured = -float(view.vertices(data)[-1, 2])
    return StudyResult(
        n_edges, measured, expected, measured / expected - 1.0, view.length(data) / length - 1.0, sps
    )


def helix_study(
    edges_per_turn: int,
    *,
    turns: int = 3,
    coil_radius: float = 0.01,
    pitch: float = 0.004,
    radius: float = 1e-3,
    young: float = 1e9,
    poisson: float = 0.49,
    density: float = 1300.0,
    timestep: float = DEFAULT_TIMESTEP,
    settle: float = 1.0,
) -> StudyResult:
    """Axial stiffness of a close-coiled helical spring vs ``k = G d⁴ / (8 D³ N)`` (gravity off).

    The coil is clamped at its first edge; its far end turns radially inward into a straight 3-edge arm so that the
    axial force (1 % of the coil height worth of extension) acts on the spring axis — a force at the wire would also
    tilt the spring. The arm's own cantilever compliance ``R³ / (3 E I)`` is subtracted from the measured extension.
    """
    psi = np.linspace(0.0, 2.0 * math.pi * turns, turns * edges_per_turn + 1)
    coil = np.stack(
        [coil_radius * np.cos(psi), coil_radius * np.sin(psi), pitch * psi / (2.0 * math.pi)], axis=1
    )
    s = np.linspace(1.0, 0.0, 4)[1:]
    arm = np.stack([coil[-1, 0] * s, coil[-1, 1] * s, np.full(3, coil[-1, 2])], axis=1)
    pts = np.vstack([coil, arm])
    rod = RodSpec(name="helix", points=pts, radius=radius, young=young, poisson=poisson, density=density)
    model = build_rod_model([rod], timestep=timestep, gravity=(0.0, 0.0, 0.0))
    data = mujoco.MjData(model)
    expected = rod.shear_modulus * (2.0 * radius) ** 4 / (8.0 * (2.0 * coil_radius) ** 3 * turns)
    force = 0.01 * pitch * turns * expected
    data.xfrc_applied[model.body(f"helix_{len(pts) - 1}").id, 2] = force
    sps = _run_timed(model, data, settle)
    view = RodView(model, "helix")
    x = view.vertices(data)
    extension = float(x[-1, 2] - pts[-1, 2]) - force * coil_radius**3 / (
        3.0 * bending_stiffness(young, radius)
    )
    measured = force / extension
    return StudyResult(
        rod.n_edges, measured, expected, measured / expected - 1.0, view.length(data) / rod.length - 1.0, sps
    )
