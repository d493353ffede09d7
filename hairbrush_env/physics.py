"""Versions of the brushing physics: what ``HairBrush-v1`` … ``-v10`` and the studies' ``--physics`` set.

A change of the brushing physics is released as a new version instead of a change of the defaults, so an agent
trained on ``HairBrush-v0`` (the RL reference run, docs/rl.md) is evaluated on the physics it was trained on, and
every number measured on v0 stays reproducible. A version is a brush and a set of :class:`~hairbrush_env.hair.WigConfig`
fields applied to every wig it brushes, presets and custom wigs alike.

- ``v0``: the defaults (rigid comb, strands that do not collide with themselves, hair–hair friction 0.3).
- ``v1``: strands that collide with themselves (a curl cannot pass through its own turns), hair–hair friction 0.15
  (conditioned hair) and the comb with nylon tines that bend up to ±1.2 rad (``soft_comb``). With all three,
  repeated full strokes on coily read above F_T first and comb out to ≤ 30 % (Fig. 3.6(i)) and the full-stroke
  force grows with curliness (Fig. 3.7); with the rigid comb the slipperier strands pack onto a tine and jam
  (docs/detangling.md, *Tines that bend on* and *HairBrush-v1*).
- ``v2``: v1 with a tenth of the joint damping (0.002 s), wisps of cohesion 16 (``young`` 1.6e8 Pa) and a quadratic
  drag of water's density on the strands while they are brushed (``drag_density``, :mod:`hairbrush_env.hair.drag`).
  v1's joint damping, scaled with the mass, made the force grow with the pull speed (+78 % for 4×, Fig. 3.8); the
  drag takes out the momentum the mass scaling adds to a curl springing off a tine without resisting the slow pull
  (+30 %). Repeated full strokes then read their largest force first and comb out to ≤ 30 % on 5 of 6 series
  (Fig. 3.6(i)), and the sigmoid finishes by eq. 3.4 on curly and coily; but wavy's full stroke reads more than
  loose_curl's (Fig. 3.7) (docs/detangling.md, *HairBrush-v2*).
- ``v3``: v2 with every group a pair (``n_triples = 0``: twelve pairs of the default 24 strands) and the comb two
  tines wider to span them (``wide_soft_comb``). A comb's tines run along the brush's depth and part strands only
  by where they hang across it; one tine through a triple's axis parts one strand from the other two, whose link
  then has no way out. Under v2 those pairs kept 0.14 of curly's link after six full strokes. Under v3 repeated
  full strokes on curly and coily read their largest force first, plateau by eq. 3.4 and leave 0.16–0.19 on all
  six series, Fig. 3.6(i) whole (docs/detangling.md, *What holds the link under v2* and *HairBrush-v3*).
- ``v4``: v3 with each pair hanging straight below its roots for its own part of half a curl pitch before it curls
  (``root_run = 0.5``). Under v3 all pairs curl from their roots in one phase, so a comb put in at some start heights
  meets every pair head on and parts none (curly, seed 0: 0 of 12 at b_l 0.7 and 0.9, 12 of 12 at 0.725 and 0.95);
  under v4 it parts 9–11 of 12 at every start height tried (docs/detangling.md, *Where the comb goes in*).
- ``v5``: v4 with every curled pair hanging straight for 12 mm below its roots before v4's spread of runs
  (``root_run_min = 0.012``). Under v4 the curl of some pairs starts at the roots, above the tines of a full stroke
  (8 mm below the roots), and the link held there is never combed; coily's tines meet those pairs' coils head on at
  the insertion. With the straight 12 mm no link lies above the tines (docs/detangling.md, *HairBrush-v5*).
- ``v6``: v5 with every strand's stress-free shape turned by π/2 about its root instead of π/3 (``rest_splay``), the
  root's twist hinge first (``root_twist_first``). The two strands of a pair rest 2R apart across the tines
  (v5: R), so the tine through the group axis lies between their rest coils instead of inside both. Under v5 a full
  stroke through coily gathers both strands of every pair onto that tine and leaves them hanging on one axis, their
  turns interleaved, and the second stroke winds pairs up again. A strand hanging straight below its root is turned
  purely in twist, which at π/2 would rest the default hinge order on its gimbal lock, hence the twist first
  (docs/detangling.md, *HairBrush-v6*).
- ``v7``: v6 with the curls of the curliest presets smaller (``preset_fields``): ``curl_radius`` 10 mm on
  ``tight_curl``, 9 mm on ``coily``, 11 mm on ``held_out_tight`` (12 mm on all three before), at the same R/P, with
  ``max_edges`` 48 so they keep 8 edges per turn, and their rest shapes turned by 2π/3 so that each coil still
  reaches round the tine between groups. Under v6 a full stroke's force is the force that draws curls straight over
  the tines, which grows with the curls' curvature (≈ 1/R once P ≪ 2πR), not with R/P: curly, tight_curl and
  coily, all at R = 12 mm, read the same 11.7–12.3 N. Hair types are told apart by curvature (tighter curls are
  smaller as well as steeper), and with it Fig. 3.7 orders by curliness (docs/detangling.md, *HairBrush-v7*).
  Custom wigs and the other presets are v6's.
- ``v8``: v7 with the ``smooth_comb``, whose tines hair slides on at its own friction 0.15. MuJoCo takes the larger
  of two geoms' coefficients, so under v1–v7 hair slid on the tines at their 0.3. A curl with a tine pulled through
  it is a screw: it turns round the tine only while μ < tan λ = P / (2π R), and otherwise locks on it and is dragged
  and drawn straight (:mod:`hairbrush_env.studies.screw_lock`). At 0.3 tight_curl's (0.25) and coily's (0.20) curls
  locked and curly's (0.32) nearly did, at any start height: their short strokes read almost what full ones read.
  At 0.15 every preset's curls turn (docs/detangling.md, *HairBrush-v8*).
- ``v9``: v8 with the strands' drag acting on the velocity across them only (``drag_normal_only``, the cross-flow
  principle of a slender cylinder's pressure drag) and the ``springy_comb``, whose tines keep a tenth of v1's hinge
  damping (ζ ≈ 0.075). A curl letting a tine through turns about its own axis once per pitch of travel, 4× as fast
  at a 4× faster pull; its wire then moves nearly along itself, so v8's drag of the whole velocity braked it
  (sin³ λ of that under v9's: 0.028 on curly), and the tines' damping read the faster give as force. Under v8 curly's
  full stroke moved +52 % for 0.05 → 0.2 m/s (Fig. 3.8); under v9 +15 % (docs/detangling.md, *HairBrush-v9*).
- ``v10``: v9 whose strokes read the load cell as thesis Algorithm 1 does, only while the brush is above the bottom
  of the hair (``SceneConfig.read_in_hair``); the abort and a stroke's ``max_force`` see those samples, the pull
  goes on as under v9 (a sample below the hair no longer aborts it) and pain is counted over all of it. The hair and
  the brush are v9's. Under v9 a short stroke read the force of the strands it had hooked and dragged below their
  rest free ends (7–10 cm on curly's b_l 0.33), after it had left the hair: curly's b_l = 0.33 strokes, seeds 0–2,
  read 3.45–4.24 N there and 0.54–0.70 N in the hair (docs/detangling.md, *HairBrush-v10*).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any


@dataclass(frozen=True)
class PhysicsVersion:
    """A brush preset and the WigConfig fields a version sets on every wig."""

    name: str
    brush: str = "comb"
    wig_fields: Mapping[str, Any] = field(default_factory=dict)
    #: WigConfig fields set on the named presets only (after ``wig_fields``): how a version re-sizes a preset's
    #: curls. A wig given by name, or as a config equal to that preset, gets them; any other config is used as given.
    preset_fields: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    #: SceneConfig fields the version sets on every scene: how its strokes are run and read (v10's
    #: ``read_in_hair``).
    scene_fields: Mapping[str, Any] = field(default_factory=dict)
    #: What the version changes, in a few words (the CLI's help texts).
    summary: str = ""

    def env_kwargs(self) -> dict[str, Any]:
        """Constructor arguments of the brushing envs for this version (empty for v0: the envs' defaults)."""
        out: dict[str, Any] = {}
        if self.brush != "comb":
            out["brush"] = self.brush
        if self.wig_fields:
            out["wig_fields"] = dict(self.wig_fields)
        if self.preset_fields:
            out["preset_fields"] = {name: dict(f) for name, f in self.preset_fields.items()}
        if self.scene_fields:
            out["scene_fields"] = dict(self.scene_fields)
        return out

    def wig(self, wig: Any):
        """The :class:`~hairbrush_env.hair.WigConfig` of ``wig`` (a preset name or a config) under this version."""
        from .hair import get_wig

        config = get_wig(wig)  # "wig: unknown preset ..." as it is
        try:
            return versioned_wig(config, self.wig_fields, self.preset_fields)
        except ValueError as exc:  # e.g. an odd n_strands under v3, which has no triples to make it up
            sets = ", ".join(f"{k}={v!r}" for k, v in self.wig_fields.items())
            raise ValueError(
                f"wig {config.name!r} under physics {self.name} (which sets {sets}): {exc}"
            ) from None

    def scene_config(self, wig: Any, **fields: Any):
        """A :class:`~hairbrush_env.scene.SceneConfig` brushing ``wig`` under this version."""
        from .scene_build import SceneConfig

        return SceneConfig(wig=self.wig(wig), brush=self.brush, **{**self.scene_fields, **fields})


# Each version's wig fields are the one before's plus what it changes.
_V1_WIG_FIELDS: Mapping[str, Any] = {"self_collision": True, "friction": 0.15}
_V2_WIG_FIELDS: Mapping[str, Any] = {
    **_V1_WIG_FIELDS,
    "damping": 0.002,
    "young": 1.6e8,
    "drag_density": 1000.0,
}

_V3_WIG_FIELDS: Mapping[str, Any] = {**_V2_WIG_FIELDS, "n_triples": 0}
_V4_WIG_FIELDS: Mapping[str, Any] = {**_V3_WIG_FIELDS, "root_run": 0.5}
_V5_WIG_FIELDS: Mapping[str, Any] = {**_V4_WIG_FIELDS, "root_run_min": 0.012}
_V6_WIG_FIELDS: Mapping[str, Any] = {**_V5_WIG_FIELDS, "rest_splay": math.pi / 2, "root_twist_first": True}
# v7's smaller curls: 8 edges per turn needs up to 42 edges (coily, 0.30 m at R = 9 mm), above the default cap of 32.
# Each strand's helix axis rests R (1 − cos ψ) across the tines from its group's: at v6's ψ = π/2 a coil of R ≤ 10 mm
# no longer reaches round the tine between groups (20 mm out; the coil spans 0–2R), nothing holds it on its side, and
# a full stroke gathers both strands of a pair onto the middle tine again (coily, 9 mm: second stroke 18.9 N after
# 18.3). At ψ = 2π/3 the coil spans 0.5R–2.5R: clear of the middle tine, round its own (2.5R > 20 mm from R = 8 mm).
_V7_REST_SPLAY = 2.0 * math.pi / 3.0
_V7_PRESET_FIELDS: Mapping[str, Mapping[str, Any]] = {
    "tight_curl": {"curl_radius": 0.010, "max_edges": 48, "rest_splay": _V7_REST_SPLAY},
    "coily": {"curl_radius": 0.009, "max_edges": 48, "rest_splay": _V7_REST_SPLAY},
    "held_out_tight": {"curl_radius": 0.011, "max_edges": 48, "rest_splay": _V7_REST_SPLAY},
}

PHYSICS: Mapping[str, PhysicsVersion] = {
    "v0": PhysicsVersion("v0", summary="rigid comb, hair-hair friction 0.3"),
    "v1": PhysicsVersion(
        "v1",
        brush="soft_comb",
        wig_fields=_V1_WIG_FIELDS,
        summary="self-colliding strands, hair-hair friction 0.15, soft comb",
    ),
    "v2": PhysicsVersion(
        "v2",
        brush="soft_comb",
        wig_fields=_V2_WIG_FIELDS,
        summary="v1 with a tenth of the joint damping, stiffer wisps and drag on the strands",
    ),
    "v3": PhysicsVersion(
        "v3",
        brush="wide_soft_comb",
        wig_fields=_V3_WIG_FIELDS,
        summary="v2 with every group a pair and a comb two tines wider",
    ),
    "v4": PhysicsVersion(
        "v4",
        brush="wide_soft_comb",
        wig_fields=_V4_WIG_FIELDS,
        summary="v3 with each pair curling from a different distance below its roots",
    ),
    "v5": PhysicsVersion(
        "v5",
        brush="wide_soft_comb",
        wig_fields=_V5_WIG_FIELDS,
        summary="v4 with every pair hanging straight for 12 mm below its roots",
    ),
    "v6": PhysicsVersion(
        "v6",
        brush="wide_soft_comb",
        wig_fields=_V6_WIG_FIELDS,
        summary="v5 with each strand's rest shape turned by pi/2 about its root (twist hinge first), so a pair's "
        "strands rest apart across the tines",
    ),
    "v7": PhysicsVersion(
        "v7",
        brush="wide_soft_comb",
        wig_fields=_V6_WIG_FIELDS,
        preset_fields=_V7_PRESET_FIELDS,
        summary="v6 with smaller curls on tight_curl, coily and held_out_tight (curvature grows with curliness), "
        "their rest shapes turned by 2pi/3",
    ),
    "v8": PhysicsVersion(
        "v8",
        brush="smooth_comb",
        wig_fields=_V6_WIG_FIELDS,
        preset_fields=_V7_PRESET_FIELDS,
        summary="v7 with tines that hair slides on at its own friction 0.15 (curls turn round a tine instead of "
        "locking on it)",
    ),
    "v9": PhysicsVersion(
        "v9",
        brush="springy_comb",
        wig_fields={**_V6_WIG_FIELDS, "drag_normal_only": True},
        preset_fields=_V7_PRESET_FIELDS,
        summary="v8 with the strands' drag on the velocity across them only (a curl turning round a tine feels "
        "a fraction of it) and tines that spring back (a tenth of the hinge damping)",
    ),
    "v10": PhysicsVersion(
        "v10",
        brush="springy_comb",
        wig_fields={**_V6_WIG_FIELDS, "drag_normal_only": True},
        preset_fields=_V7_PRESET_FIELDS,
        scene_fields={"read_in_hair": True},
        summary="v9 with strokes that read the load cell only while the brush is above the bottom of the hair "
        "(Algorithm 1); the pull and pain counts are v9's",
    ),
}


def preset_fields_of(wig: Any, preset_fields: Mapping[str, Mapping[str, Any]] | None) -> dict[str, Any]:
    """The fields ``preset_fields[name]`` when ``wig`` (a preset name or a config) is the preset ``name``: given by
    its name, or as a config equal to the preset; ``{}`` otherwise. A config that differs from its preset (a custom
    wig, or a preset with fields of your own) gets none: a version re-sizes its presets, not your wigs. They are set
    after the version's ``wig_fields`` (a preset's own fields win). ``ValueError`` names a bad entry."""
    from .hair import get_wig

    config = get_wig(wig)
    if not preset_fields:
        return {}
    if not isinstance(preset_fields, Mapping):
        raise ValueError(
            f"preset_fields: expected a mapping of preset name to WigConfig fields, got {preset_fields!r}"
        )
    own: dict[str, Any] = {}
    for name, fields in preset_fields.items():
        try:
            preset = get_wig(name)
        except ValueError as exc:
            raise ValueError(f"preset_fields: {exc}") from None
        if not isinstance(fields, Mapping):
            raise ValueError(
                f"preset_fields[{name!r}]: expected a mapping of WigConfig fields, got {fields!r}"
            )
        try:
            preset.replace(**fields)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"preset_fields[{name!r}]: {exc}") from None
        if config == preset:
            own = dict(fields)
    return own


def versioned_wig(
    wig: Any, wig_fields: Mapping[str, Any] | None, preset_fields: Mapping[str, Mapping[str, Any]] | None
):
    """The :class:`~hairbrush_env.hair.WigConfig` of ``wig`` (a preset name or a config) with ``wig_fields`` set, and
    then, when ``wig`` as given is one of the presets ``preset_fields`` names, that preset's own fields
    (:func:`preset_fields_of`). A config that already is such a versioned preset is returned as it is: setting
    ``wig_fields`` again would undo a preset's own value of a field both set. What :meth:`PhysicsVersion.wig` and
    the envs' ``wig_fields`` / ``preset_fields`` arguments both do."""
    from .hair import get_wig

    config = get_wig(wig)
    fields = {**(wig_fields or {}), **preset_fields_of(config, preset_fields)}
    if not fields:
        return config
    for name, own in (preset_fields or {}).items():
        if config == get_wig(name).replace(**{**(wig_fields or {}), **own}):
            return config
    return config.replace(**fields)


def physics_help() -> str:
    """One line per version for the CLI's help texts: ``v0 (...); v1 (...); ...``."""
    return "; ".join(f"{v.name} ({v.summary})" for v in PHYSICS.values())


def get_physics(name: str | PhysicsVersion) -> PhysicsVersion:
    """The version called ``name``; ``ValueError`` naming the valid ones otherwise."""
    if isinstance(name, PhysicsVersion):
        return name
    if name not in PHYSICS:
        raise ValueError(f"physics: unknown version {name!r}; valid: {', '.join(PHYSICS)}")
    return PHYSICS[name]


def claim_physics(out: str | Path, name: str, *, resuming: bool) -> None:
    """Record the physics version of a study in ``out/physics.json``; refuse to resume (add rows to) a study that
    ran under another version. Studies written before the file existed ran under v0."""
    from .io import write_text

    get_physics(name)
    meta = Path(out) / "physics.json"
    if meta.exists():
        had = json.loads(meta.read_text()).get("physics", "v0")
    else:
        had = "v0" if resuming else name
    if had != name:
        raise ValueError(f"physics: {out} holds results under {had}; got {name!r} (use another --out)")
    write_text(meta, json.dumps({"physics": name}) + "\n")
