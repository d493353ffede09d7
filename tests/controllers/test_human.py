"""The human-like baseline: short strokes from the free ends upward, re-brushing while the force stays high."""

from __future__ import annotations

import numpy as np
import pytest

from controllers.human import HumanPolicy


class _Env:
    """The part of HairBrush-v0 the policy uses: b_l <-> action (identity here) and F_T."""

    force_threshold = 10.0

    def brush_length_to_action(self, b_l: float) -> np.ndarray:
        return np.array([b_l], np.float32)


def _schedule(forces: list[float], **kw) -> list[float]:
    policy = HumanPolicy(_Env(), **kw)
    out = [float(policy.act({})[0])]
    for f in forces:
        out.append(float(policy.act({"max_force": np.array([f], np.float32)})[0]))
    return out


def test_works_up_from_the_free_ends_when_brushing_is_easy():
    assert _schedule([1.0, 1.0, 1.0, 1.0, 1.0]) == pytest.approx([0.25, 0.5, 0.75, 1.0, 1.0, 1.0])


def test_rebrushes_a_section_while_the_force_stays_high_but_never_stalls():
    # above the comfort level (F_T / 2 = 5 N) the same section is brushed again, at most max_repeats times
    assert _schedule([6.0, 6.0, 2.0]) == pytest.approx([0.25, 0.25, 0.25, 0.5])
    assert _schedule([9.0] * 4, max_repeats=2) == pytest.approx([0.25, 0.25, 0.25, 0.5, 0.5])


def test_pulls_through_and_checks_its_arguments():
    assert HumanPolicy.abort_force is None
    bad = (
        ({"step": 0.0}, "step"),
        ({"comfort_force": -1.0}, "comfort_force"),
        ({"max_repeats": -1}, "max_repeats"),
    )
    for kw, name in bad:
        with pytest.raises(ValueError, match=name):
            HumanPolicy(_Env(), **kw)
    with pytest.raises(ValueError, match="stroke-level"):
        HumanPolicy(object())
    policy = HumanPolicy(_Env())
    policy.act({})
    with pytest.raises(ValueError, match="max_force"):
        policy.act({})
