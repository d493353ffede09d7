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
    wig = get_wig("curly").replace(name="test_rep", n_strands=4, n_triples=0, length=0.2)
    sim = BrushingSim(SceneConfig(wig=wig))
    seen = []
    rows = repeated_strokes(sim, seed=0, n_strokes=2, on_stroke=seen.append)
    assert rows == seen and [r["stroke"] for r in rows] == [0, 1, 2]
    # no strand passes through another in the shake, so the pairs keep their built link; the prestressed pairs wind
    # a little beyond it (measured 4.73 of 4.21 built)
    assert 0.9 * sim.layout.n_links < rows[0]["entanglement"] < 1.2 * sim.layout.n_links
    for r in rows[1:]:
        assert r["max_force"] > 0 and not r["aborted"] and not r["diverged"] and r["cpu_s"] > 0
        assert r["crossings"] == 0 and r["min_hair_hair"] > 0.5 and not math.isnan(r["min_hair_bristle"])
        assert r["entanglement"] == pytest.approx(r["entwined"] + r["made"])
    with pytest.raises(ValueError, match="n_strokes"):
        repeated_strokes(sim, n_strokes=0)
    n_steps = sim.n_steps
    with pytest.raises(ValueError, match="y must be"):
        repeated_strokes(sim, n_strokes=2, y=[0.0, 0.5])  # rejected before any stroke
    assert sim.n_steps == n_steps
    sideways = repeated_strokes(sim, seed=0, n_strokes=2, y=[0.0, 0.01], monitor=False)
    assert sim.brush_position()[1] == pytest.approx(0.01, abs=1e-3)  # stroke 2 at y = 0.01
    assert all(0 <= r["still_entwined"] <= len(sim.layout.pairs) for r in sideways)


@pytest.fixture(scope="module")
def curly_first_stroke() -> tuple[BrushingSim, list[dict]]:
    sim = BrushingSim(SceneConfig(wig="curly"))
    return sim, repeated_strokes(sim, seed=0, n_strokes=1)


def test_default_curly_first_stroke_combs_out_half(curly_first_stroke):
    """Fig. 3.6(i), first stroke, on the default wig and comb (curly, seed 0, a full stroke without abort): the
    pre-brushed wig holds all its built link (45.9 against 41.0 built; the prestressed triples wind beyond it), one
    stroke combs out about half (measured 0.52 left) through the free ends: no strand crosses another, and none comes
    closer than half the sum of radii to another at any physics step (measured 1.18)."""
    sim, rows = curly_first_stroke
    assert rows[0]["entanglement"] > 0.95 * sim.layout.n_links
    assert rows[1]["entanglement"] <= 0.67 * rows[0]["entanglement"]
    assert rows[1]["crossings"] == 0 and rows[1]["min_hair_hair"] >= 0.5


def _six_strokes(wig: str, seed: int) -> list[dict]:
    return repeated_strokes(BrushingSim(SceneConfig(wig=wig)), seed=seed, n_strokes=6)


@pytest.fixture(scope="module")
def curly_six_strokes() -> dict[int, list[dict]]:
    return {seed: _six_strokes("curly", seed) for seed in (0, 1, 2)}


_NOT_COMBED_OUT = (
    "with the pre-brushed wigs holding their full link (docs/detangling.md, Correction), six full strokes leave "
    "0.59 / 0.57 / 0.68 of curly's entanglement (seeds 0-2; every stroke after the first removes none, 13-15 of "
    "the 15 pairs stay wound) and the force peaks at the second stroke (8.3-10.1 N after 5.6-6.2 N)"
)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.xfail(strict=True, raises=AssertionError, reason=_NOT_COMBED_OUT)
def test_fig_3_6_full_strokes_detangle(curly_six_strokes, seed: int):
    """Fig. 3.6(i) on curly, seeds 0–2: six full strokes without abort; every later stroke reads less than the first,
    at most 30 % of the entanglement is left (``hairbrush repeat --wigs curly --seeds 3 --out ...``) and no strand
    crosses another."""
    rows = curly_six_strokes[seed]
    assert all(r["crossings"] == 0 for r in rows[1:])
    forces = [r["max_force"] for r in rows[1:]]
    assert max(forces[1:]) < forces[0]
    assert rows[-1]["entanglement"] <= 0.3 * rows[0]["entanglement"]


@pytest.mark.slow
@pytest.mark.xfail(strict=True, raises=AssertionError, reason=_NOT_COMBED_OUT)
def test_fig_3_6_force_plateaus_within_six_strokes(curly_six_strokes):
    """Eq. 3.4 (|Δf_max| < 0.4 N) is met within six full strokes on every seed (measured: on none)."""
    assert all(
        plateau_stroke([r["max_force"] for r in rows[1:]]) is not None for rows in curly_six_strokes.values()
    )


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="coily does not comb out to 30 %: after six full strokes seed 0 holds 0.46 of its entanglement (0.41 after "
    "the first stroke, then no more leaves; 15 of 15 pairs still wound); docs/detangling.md",
)
def test_fig_3_6_coily_detangles():
    rows = _six_strokes("coily", 0)
    assert rows[-1]["entanglement"] <= 0.3 * rows[0]["entanglement"]


def test_run_repeated_writes_resumable_series(tmp_path):
    """The ``hairbrush repeat`` study: one CSV row per stroke and series, a summary and a plot; a rerun keeps the
    complete series (same rows, nothing simulated) and re-runs an incomplete one."""
    from hairbrush_env.studies.repeated_strokes import run_repeated

    wig = get_wig("curly").replace(name="test_run_rep", n_strands=2, n_triples=0, length=0.12)
    rows = run_repeated([wig], seeds=[0], n_strokes=2, out=tmp_path, progress=False)
    assert [(r["wig"], r["seed"], r["stroke"]) for r in rows] == [("test_run_rep", 0, k) for k in range(3)]
    assert (tmp_path / "repeat.png").stat().st_size > 0 and "test_run_rep" in (
        tmp_path / "summary.md"
    ).read_text()
    again = run_repeated([wig], seeds=[0], n_strokes=2, out=tmp_path, progress=False)
    assert [r["cpu_s"] for r in again] == pytest.approx([r["cpu_s"] for r in rows])
    with pytest.raises(ValueError, match="wigs"):
        run_repeated(["bogus"], out=tmp_path)


@pytest.mark.parametrize(
    ("argv", "flag"),
    [
        (["--strokes", "0"], "--strokes"),
        (["--seeds", "0"], "--seeds"),
        (["--brush-length", "1.5"], "--brush-length"),
        (["--wigs", "bogus"], "bogus"),
    ],
)
def test_repeat_command_refuses_bad_input_before_simulating(argv, flag, tmp_path, capsys):
    from hairbrush_env.cli import main

    with pytest.raises(SystemExit) as exc:
        main(["repeat", "--out", str(tmp_path), "--quiet", *argv])
    assert exc.value.code == 2 and flag in capsys.readouterr().err
    assert not (tmp_path / "repeat.csv").exists()
