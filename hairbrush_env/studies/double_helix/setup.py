"""Geometry, material and numerics of one combing run: :class:`CombingSetup` and :func:`replace_setup` (CLI
strings → typed fields)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields, replace
from typing import Any

__all__ = ["CombingSetup", "replace_setup"]


@dataclass(frozen=True)
class CombingSetup:
    """Geometry, material and numerics of one combing run (dimensionless ratios as in thesis Fig. 2.2b).

    Parameters
    ----------
    P_over_r, R_over_r, t_over_r : float
        π1 = P/r (pitch), π2 = R/r (helix radius, half the centerline distance; ≥ 1), π3 = t/r (tine radius).
        Thesis main-text runs use t/r = 0.9.
    q : float or None
        Pitches between the tine insertion point and the free end; ``None`` = insertion at mid-height (thesis
        Figs 2.2–2.3). Needs ``q * P < height``.
    speed : float
        Tine speed [m/s].
    friction : float
        Coulomb friction of all contacts (0 = frictionless, the thesis's simulations; > 0 uses condim 3).
    edges_per_pitch : int
        Discretization: rod edges per helix pitch (per turn of one strand around the other).
    radius, height, young, poisson, linear_density : float
        r [m], h [m], E [Pa], ν, mass per length [kg/m] of one filament.
    drag : float
        Viscous drag per unit length [N s/m²] on the strand vertices (quasi-static damping).
    bend_damping : float
        MuJoCo Rayleigh damping of bending/torsion [s].
    mass_scale : float
        Multiply mass by this and divide gravity by it (m·g constant; the thesis used 7.52e5 for stability).
    l0 : float
        Reference length of f = F l0²/B [m].
    timestep : float
        Simulation step [s].
    contact_timeconst : float
        Time constant of all contacts (``solref[0]``) [s]; stiffness ∝ mass / timeconst². MuJoCo needs ≥ 2
        ``timestep``. 4 ms (rods.py advice for thin hair) holds in the runs of docs/double_helix.md with P/r ≥ 24 but
        for the longest
        stroke (q = 12); the tight P/r = 18 helix overloads it (one strand is pinched through the other at the tine
        at release: ``strand_crossings``), and 2 ms at a 1 ms step holds.
    settle_time : float
        Relaxation under gravity around the inserted, fixed tine before it moves [s].
    samples : int
        Number of recorded samples along the stroke (force is averaged over the steps between samples).
    snapshot_x : tuple of float
        Tine positions x = d/D at which link-density snapshots Δλ(s)/λ0 are reported.
    max_stroke : float
        Safety limit of the tine stroke in units of the height.
    """

    P_over_r: float = 24.0
    R_over_r: float = 1.0
    t_over_r: float = 0.9
    q: float | None = None
    speed: float = 0.005
    friction: float = 0.0
    edges_per_pitch: int = 10
    radius: float = 4.25e-4
    height: float = 0.15
    young: float = 0.27e9 * 0.078
    poisson: float = 0.49
    linear_density: float = 6.65e-4
    drag: float = 0.02
    bend_damping: float = 0.0
    mass_scale: float = 100.0
    l0: float = 0.01
    timestep: float = 2e-3
    contact_timeconst: float = 4e-3
    settle_time: float = 0.4
    samples: int = 200
    snapshot_x: tuple[float, ...] = (0.0, 0.2, 0.4, 0.6, 0.8)
    max_stroke: float = 1.5

    def __post_init__(self) -> None:
        def check(name: str, lo: float | None = None, *, strict: bool = True) -> None:
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"CombingSetup.{name} must be a finite number, got {v!r}")
            if lo is not None and (v <= lo if strict else v < lo):
                raise ValueError(f"CombingSetup.{name} must be {'>' if strict else '>='} {lo}, got {v!r}")

        for name in ("P_over_r", "t_over_r", "speed", "radius", "height", "young", "linear_density"):
            check(name, 0.0)
        for name in ("l0", "timestep", "contact_timeconst", "mass_scale", "samples", "max_stroke"):
            check(name, 0.0)
        if self.contact_timeconst < 2.0 * self.timestep:
            raise ValueError(
                "CombingSetup.contact_timeconst must be >= 2 timestep (MuJoCo would silently raise it): "
                f"got {self.contact_timeconst!r} with timestep {self.timestep!r}"
            )
        for name in ("friction", "drag", "bend_damping", "settle_time"):
            check(name, 0.0, strict=False)
        check("R_over_r", 1.0, strict=False)
        check("poisson", 0.0, strict=False)
        if self.poisson >= 0.5:
            raise ValueError(f"CombingSetup.poisson must be < 0.5 (MuJoCo), got {self.poisson!r}")
        if int(self.edges_per_pitch) != self.edges_per_pitch or self.edges_per_pitch < 4:
            raise ValueError(
                f"CombingSetup.edges_per_pitch must be an integer >= 4, got {self.edges_per_pitch!r}"
            )
        if int(self.samples) != self.samples or self.samples < 10:
            raise ValueError(f"CombingSetup.samples must be an integer >= 10, got {self.samples!r}")
        if self.q is not None:
            check("q", 0.0)
            if self.q * self.pitch >= self.height - 0.5 * self.pitch:
                raise ValueError(
                    "CombingSetup.q must leave at least half a pitch above the tine: "
                    f"q·P = {self.q * self.pitch:.4g} m but height = {self.height:.4g} m (raise height)"
                )
        if not all(0.0 <= x < 1.0 for x in self.snapshot_x):
            raise ValueError(f"CombingSetup.snapshot_x must lie in [0, 1), got {self.snapshot_x!r}")
        object.__setattr__(self, "snapshot_x", tuple(float(x) for x in self.snapshot_x))

    # derived geometry ---------------------------------------------------------------------------------
    @property
    def pitch(self) -> float:
        """P [m]."""
        return self.P_over_r * self.radius

    @property
    def helix_radius(self) -> float:
        """R [m]."""
        return self.R_over_r * self.radius

    @property
    def tine_radius(self) -> float:
        """t [m]."""
        return self.t_over_r * self.radius

    @property
    def turns(self) -> float:
        """Pitches over the height, h/P (≈ the initial Lk)."""
        return self.height / self.pitch

    @property
    def insertion_depth(self) -> float:
        """Depth of the tine below the clamp at insertion [m]."""
        return 0.5 * self.height if self.q is None else self.height - self.q * self.pitch

    def q_near_clamp(self) -> float:
        """The largest q allowed: the tine enters just over half a pitch below the clamp.

        The thesis's simulations insert the tine "close to the clamped end" (§2.3); only then can one stroke expel
        nearly all the link, because the link between clamp and tine cannot pass the tine (``lk_above``, about
        half a link here). Half a pitch is as close as the insertion opening allows: it is a Gaussian of width
        P/4 (``model.bulge``), so at the clamp it is down to 2 % and the clamped ends stay on the helix.
        """
        return self.height / self.pitch - 0.51

    @property
    def q_effective(self) -> float:
        """Pitches between insertion point and free end."""
        return (self.height - self.insertion_depth) / self.pitch

    @property
    def bending(self) -> float:
        """B = E π r⁴ / 4 of one filament [N m²]."""
        return self.young * math.pi * self.radius**4 / 4.0

    @property
    def twisting(self) -> float:
        """C = G π r⁴ / 2 with G = E / (2 (1 + ν)) [N m²]."""
        return self.young / (2.0 * (1.0 + self.poisson)) * math.pi * self.radius**4 / 2.0

    @property
    def force_scale(self) -> float:
        """B / l0² [N]: f = F / force_scale."""
        return self.bending / self.l0**2

    def key(self) -> dict[str, Any]:
        """All fields as a JSON-friendly dict (used as the cache key of sweeps)."""
        d = asdict(self)
        d["snapshot_x"] = list(self.snapshot_x)
        return d


def replace_setup(setup: CombingSetup, **changes: Any) -> CombingSetup:
    """``dataclasses.replace`` that accepts string values from the CLI.

    For ``q``: ``"none"`` / ``"mid"`` → ``None`` (mid-height insertion); ``"clamp"`` → :meth:`CombingSetup.q_near_clamp`
    of the setup after the other changes.
    """
    typed: dict[str, Any] = {}
    near_clamp = False
    for k, v in changes.items():
        if k not in {f.name for f in fields(CombingSetup)}:
            raise ValueError(f"CombingSetup has no field {k!r}")
        if isinstance(v, str):
            if k == "q" and v.lower() == "clamp":
                near_clamp, v = True, None
            elif k == "q" and v.lower() in ("none", "mid", "midpoint"):
                v = None
            elif k in ("edges_per_pitch", "samples"):
                v = int(v)
            elif k == "snapshot_x":
                v = tuple(float(s) for s in v.split(";"))
            else:
                v = float(v)
        typed[k] = v
    if near_clamp:
        out = replace(setup, **typed)
        return replace(out, q=out.q_near_clamp())
    return replace(setup, **typed)
