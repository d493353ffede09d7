"""Collision-bit convention shared by every part of the hair-brushing scene.

MuJoCo lets geoms ``a`` and ``b`` collide iff ``(a.contype & b.conaffinity) or (b.contype & a.conaffinity)``.
Each part sets ``contype`` to the one bit of its *role* and ``conaffinity`` to the roles it must touch:

==========  ====  =========================================  ==========  ===========
role        bit   geoms                                      contype     conaffinity
==========  ====  =========================================  ==========  ===========
HAIR        1     hair / wig segments                        1           TOOL | ENV (= 10)
TOOL        2     brush bristles                             2           HAIR (= 1)
TOOL        2     brush head plate                           2           HAIR | ENV (= 9)
ROBOT       4     arm links, brush mount                     4           ENV (= 8)
ENV         8     head proxy (skull, neck, base), floor      8           HAIR | TOOL | ROBOT (= 7)
(none)      -     scalp patch (roots sit on it)              0           TOOL | ROBOT (= 6)
==========  ====  =========================================  ==========  ===========

Consequences (all intended): bristles touch hair (and the skull), never each other; the arm never touches
hair nor itself (it only has to stay out of the head); hair touches tools and the head.  Hair-hair contact
is opt-in: give hair ``conaffinity = HAIR | TOOL | ENV`` (= 11).
"""

from __future__ import annotations

HAIR = 1 << 0
TOOL = 1 << 1
ROBOT = 1 << 2
ENV = 1 << 3

#: ``(contype, conaffinity)`` per geom role.
HAIR_GEOM = (HAIR, TOOL | ENV)
HAIR_GEOM_SELF_COLLIDING = (HAIR, HAIR | TOOL | ENV)
BRISTLE_GEOM = (TOOL, HAIR)
BRUSH_HEAD_GEOM = (TOOL, HAIR | ENV)
ROBOT_GEOM = (ROBOT, ENV)
ENV_GEOM = (ENV, HAIR | TOOL | ROBOT)
# contype 0: the filter is symmetric, so any bit that hair's conaffinity holds would make roots collide.
SCALP_GEOM = (0, TOOL | ROBOT)


def collides(a: tuple[int, int], b: tuple[int, int]) -> bool:
    """MuJoCo's contype/conaffinity filter for two ``(contype, conaffinity)`` pairs."""
    return bool((a[0] & b[1]) or (b[0] & a[1]))
