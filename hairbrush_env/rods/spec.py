"""What a rod is: geometry and material (:class:`RodSpec`), section stiffnesses and polyline helpers.

A :class:`RodSpec` says nothing about how MuJoCo represents the rod; its ``kind`` picks the representation
(:mod:`hairbrush_env.rods.chain`, the default, or :mod:`hairbrush_env.rods.flex`) and
:func:`hairbrush_env.rods.add_rod` builds it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import mujoco
import numpy as np

__all__ = [
    "DEFAULT_N_EDGES",
    "EDGE_SOLREF",
    "ROD_KINDS",
    "RodKind",
    "RodSpec",
    "bending_stiffness",
    "polyline_length",
    "resample_polyline",
    "resolve_body",
    "shear_modulus",
    "straight_rod_points",
    "twisting_stiffness",
]

RodKind = Literal["chain", "flex"]
ROD_KINDS: tuple[str, ...] = ("chain", "flex")
"""Rod representations: ``"chain"`` (capsule bodies, three hinges a vertex) and ``"flex"`` (1D flex DER)."""

DEFAULT_N_EDGES = 20
"""Edges per (straight) rod; the gravity cantilever is within 0.1 % (chain) / 0.4 % (flex) of Euler–Bernoulli."""

EDGE_SOLREF = (1e-4, 1.0)
"""Flex edge-equality ``solref``: stiff enough for < 1e-4 relative stretch (the MuJoCo default 0.02 stretched 4.6 %)."""


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
        Rod name; also the prefix of the generated bodies and joints (see :func:`hairbrush_env.rods.add_rod`).
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
        Stiffness-proportional damping of bending/torsion [s]: a chain's joint damping is ``damping · k`` for joint
        stiffness ``k``; a flex uses it as MuJoCo's ``elasticity damping`` (Rayleigh).
    quadratic_damping : float
        Stiffness-proportional *quadratic* damping of bending/torsion [s²] (chain rods only): a joint of stiffness
        ``k`` turning at ``ω`` feels ``−quadratic_damping · k · ω|ω|`` (MuJoCo's polynomial joint damping), as a
        segment whipping through air does. It damps fast motion (a curl springing back off a tine) and barely the
        slow one (a pull), so it dissipates without making forces depend on the pull speed the way ``damping``
        does. Not scaled by ``mass_scale``.
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
        Let non-adjacent elements of the same rod collide with each other (off by default, as for the flex).
    margin : float
        Contact margin [m] of the rod's geoms. MuJoCo 4.0.1 **adds** the margins of the two geoms of a contact, so
        two rods with margin ``m`` touch from ``2 m`` apart (see :mod:`hairbrush_env.collision`).
    contact_solref, contact_solimp : tuple of float, optional
        Contact ``solref`` / ``solimp`` of the flex (``None``: MuJoCo defaults ``(0.02, 1)`` /
        ``(0.9, 0.95, 0.001, 0.5, 2)``, whose 1 mm impedance width lets a rod sink ~1 mm into a capsule — more than a
        hair's radius; for thin hair use e.g. ``(0.004, 1)`` and ``(0.95, 0.99, 1e-4, 0.5, 2)``).
    edge_solref : tuple of float
        ``solref`` of the flex inextensibility constraint (keep the default unless you measured otherwise; a chain
        is inextensible by construction).
    kind : {"chain", "flex"}
        MuJoCo representation (:data:`ROD_KINDS`); ``"chain"`` is the default (faster, and more accurate per edge
        on curls, ``docs/rods.md``).
    root_rest_turn : float
        The rod's stress-free shape is ``points`` turned by this angle [rad] about the parent's z axis through the
        root (chain, clamped rods only): the rod is built in the ``points`` shape, but its root springs pull it
        towards the turned one. Wigs use it so that entwined strands are a prestressed, not a stress-free, state.
    root_twist_first : bool
        Order of the clamped root's three hinges (chain rods): ``False`` (default) bend1, twist, bend2, as at every
        other vertex; ``True`` twist, bend1, bend2. The hinges are an Euler sequence, singular where the middle angle
        reaches ±90°. A root whose first edge hangs vertically is turned by ``root_rest_turn`` purely about its
        tangent, i.e. the rest twist equals the turn: 90° puts the default order's rest reference on the lock, and
        the twist-first order at zero middle angle.
    """

    name: str
    points: np.ndarray
    radius: float
    young: float
    shear: float | None = None
    poisson: float = 0.49
    density: float = 1300.0
    damping: float = 0.0
    quadratic_damping: float = 0.0
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
    kind: RodKind = "chain"
    root_rest_turn: float = 0.0
    root_twist_first: bool = False
    mass_scale: float = 1.0

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
        if self.kind not in ROD_KINDS:
            raise ValueError(f"RodSpec.kind must be one of {ROD_KINDS}, got {self.kind!r}")
        if self.root_rest_turn != 0.0 and (self.kind != "chain" or self.clamp != "start"):
            raise ValueError("RodSpec.root_rest_turn needs a clamped chain rod (kind='chain', clamp='start')")
        if not isinstance(self.root_twist_first, bool):
            raise ValueError(f"RodSpec.root_twist_first must be a bool, got {self.root_twist_first!r}")
        if self.root_twist_first and (self.kind != "chain" or self.clamp != "start"):
            raise ValueError(
                "RodSpec.root_twist_first needs a clamped chain rod (kind='chain', clamp='start')"
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
        if not (math.isfinite(self.mass_scale) and self.mass_scale >= 1.0):
            raise ValueError(f"RodSpec.mass_scale must be a finite number >= 1, got {self.mass_scale!r}")
        if self.mass_scale != 1.0 and self.kind != "chain":
            raise ValueError("RodSpec.mass_scale needs a chain rod (kind='chain')")
        _check_finite("damping", self.damping, nonneg=True)
        _check_finite("quadratic_damping", self.quadratic_damping, nonneg=True)
        if self.quadratic_damping and self.kind != "chain":
            raise ValueError("RodSpec.quadratic_damping needs a chain rod (kind='chain')")
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


def resolve_body(spec: mujoco.MjSpec, parent: mujoco.MjsBody | str | None) -> mujoco.MjsBody:
    """The body ``parent`` names in ``spec`` (``None``: the world body); ``ValueError`` if there is none."""
    if parent is None:
        return spec.worldbody
    if isinstance(parent, str):
        body = spec.body(parent)
        if body is None:
            raise ValueError(f"parent body {parent!r} not found in spec")
        return body
    return parent
