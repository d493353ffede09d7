"""Checking that strands never pass through each other or through bristles, at every physics step.

At a 1 ms step brushed strands move up to ~2 mm per step, so a strand can cross another within one step and be on
the other side at the next 10 Hz load-cell sample: a check at 10 Hz reported 1.76 mm on a curly stroke where
per-step sampling found strands 0.36 mm apart. :class:`PassThroughMonitor` therefore runs after every physics step
(:meth:`hairbrush_env.scene.BrushingSim.add_step_observer`) and records

* the smallest hair–hair and hair–bristle centerline distances, against half the sum of the two radii — a contact
  that lets two capsules sink half-way into each other has failed;
* topological crossings of any two strands (not only the entwined pairs): a jump of ≈ 1 of a close pair's open
  Gauss integral between two steps (:class:`hairbrush_env.topology.proximity.CrossingDetector`);
* the smallest distance between two non-neighbouring segments of one strand. Strands collide with themselves only
  with ``WigConfig.self_collision``; without it a curl pressed on a tine can pass through itself (docs/detangling.md,
  *Strands pass through themselves*). :attr:`PassThroughMonitor.passed` judges pairs of strands and bristles;
  :attr:`PassThroughMonitor.self_passed` judges each strand against itself.
"""

from __future__ import annotations

import math

from .topology.proximity import Crossing, CrossingDetector, min_distance_to_segments, min_self_distance

__all__ = ["PassThroughMonitor"]


class PassThroughMonitor:
    """Per-step pass-through check of a :class:`~hairbrush_env.scene.BrushingSim`.

    Parameters
    ----------
    sim : BrushingSim
        The scene to watch; the monitor registers itself as a step observer (call :meth:`detach` to stop).
    gap : float
        Strand pairs are followed while their bounding boxes are closer than this [m].
    """

    def __init__(self, sim, *, gap: float = 5e-3) -> None:
        self.sim = sim
        self.detector = CrossingDetector(gap=gap)
        r = sim.wig.strand_radius
        self.hair_hair_sum = 2.0 * r
        self.hair_bristle_sum = r + sim.bristle_radius
        self.hair_hair_limit = 0.5 * self.hair_hair_sum
        self.hair_bristle_limit = 0.5 * self.hair_bristle_sum
        self.hair_hair = self.hair_bristle = self.hair_self = math.inf
        self.steps = 0
        sim.add_step_observer(self)

    def __call__(self, sim) -> None:
        curves = sim.hair_curve_array()
        self.detector.update(curves, float(sim.data.time))
        self.hair_hair = min(self.hair_hair, self.detector.min_distance)
        self.hair_bristle = min(self.hair_bristle, min_distance_to_segments(curves, sim.bristle_segments()))
        self.hair_self = min(self.hair_self, float(min_self_distance(curves).min()))
        self.steps += 1

    def detach(self) -> None:
        """Stop watching (the recorded minima and crossings stay)."""
        self.sim.remove_step_observer(self)

    @property
    def crossings(self) -> list[Crossing]:
        """Topological crossings seen so far (time, strand indices, jump of their Gauss integral)."""
        return self.detector.crossings

    @property
    def max_link_jump(self) -> float:
        """Largest one-step change of any close pair's Gauss integral."""
        return self.detector.max_jump

    @property
    def hair_hair_fraction(self) -> float:
        """Smallest hair–hair centerline distance / sum of the two radii."""
        return self.hair_hair / self.hair_hair_sum

    @property
    def hair_bristle_fraction(self) -> float:
        """Smallest hair–bristle centerline distance / sum of the two radii."""
        return self.hair_bristle / self.hair_bristle_sum

    @property
    def hair_self_fraction(self) -> float:
        """Smallest distance between two non-neighbouring segments of one strand / the wisp diameter."""
        return self.hair_self / self.hair_hair_sum

    @property
    def self_passed(self) -> bool:
        """No strand came closer to itself than half its diameter (a segment half-way through another)."""
        return self.hair_self > self.hair_hair_limit

    @property
    def passed(self) -> bool:
        """No crossing, and both distances above half the sum of the radii."""
        return (
            not self.crossings
            and self.hair_hair > self.hair_hair_limit
            and self.hair_bristle > self.hair_bristle_limit
        )
