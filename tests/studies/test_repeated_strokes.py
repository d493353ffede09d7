"""Repeated strokes (thesis Fig. 3.6(i)): per-stroke force, entanglement and pass-through rows; eq. 3.4 plateau."""

from __future__ import annotations

import math

import pytest

from hairbrush_env.hair import get_wig
from hairbrush_env.scene import BrushingSim, SceneConfig
from hairbrush_env.studies.repeated_strokes import plateau_stroke, repeated_strokes


def test_plateau_stroke_is_eq_3_4():
    assert plateau_stroke([14.0, 9.0, 8.8, 8.7]) == 3
    assert plateau_stroke([14.0, 9.0, 7.0]) is None
    assert plateau_stroke([5.0]) is None


def test_rows_of_a_short_run():
    wig = get_wig("curly").replace(name="test_rep", n_strands=4, n_triples=0, length=0.12)
    sim = BrushingSim(SceneConfig(wig=wig))
    seen = []
    rows = repeated_strokes(sim, seed=0, n_strokes=2, on_stroke=seen.append)
    assert rows == seen and [r["stroke"] for r in rows] == [0, 1, 2]
    assert rows[0]["entanglement"] == pytest.approx(sim.layout.n_links, rel=0.2)
    for r in rows[1:]:
        assert r["max_force"] > 0 and not r["aborted"] and not r["diverged"] and r["cpu_s"] > 0
        assert r["crossings"] == 0 and r["min_hair_hair"] > 0.5 and not math.isnan(r["min_hair_bristle"])
        assert r["entanglement"] == pytest.approx(r["entwined"] + r["made"])
    with pytest.raises(ValueError, match="n_strokes"):
        repeated_strokes(sim, n_strokes=0)
