"""Repeated strokes (thesis Fig. 3.6(i)): per-stroke force, entanglement and pass-through rows; eq. 3.4 plateau."""

from __future__ import annotations

import math

import pytest

from hairbrush_env.hair import get_wig
from hairbrush_env.scene import PAIN_THRESHOLD, BrushingSim, SceneConfig
from hairbrush_env.studies.repeated_strokes import plateau_stroke, repeated_strokes


def test_plateau_stroke_is_eq_3_4():
    assert plateau_stroke([14.0, 9.0, 8.8, 8.7]) == 3
    assert plateau_stroke([14.0, 9.0, 7.0]) is None
    assert plateau_stroke([5.0]) is None


def test_rows_of_a_short_run():
    # splay π/2: at the default π/3 the two pairs' free ends wind on in the shake to 1.22× their built link (5.14 of
    # 4.21), past the bound below; the default preparation is watched for crossings in tests/test_scene.py
    wig = get_wig("curly").replace(
        name="test_rep", n_strands=4, n_triples=0, length=0.2, rest_splay=math.pi / 2
    )
    sim = BrushingSim(SceneConfig(wig=wig))
    seen = []
    rows = repeated_strokes(sim, seed=0, n_strokes=2, on_stroke=seen.append)
    assert rows == seen and [r["stroke"] for r in rows] == [0, 1, 2]
    # no strand passes through another in the shake, so the pairs keep their built link; the prestressed pairs wind
    # a little beyond it (measured 4.72 of 4.21 built)
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


def test_default_curly_first_stroke_combs_out_most(curly_first_stroke):
    """Fig. 3.6(i), first stroke, on the default wig and comb (curly, seed 0, a full stroke without abort): the
    pre-brushed wig holds all its built link (43.8 against 41.0 built; the prestressed triples wind beyond it), one
    stroke combs out most of it (measured 0.37 left; 0.52 with every other pair's roots along the tines, docs/
    detangling.md, *Root orientation and splay*) through the free ends: no strand crosses another, and none comes
    closer than half the sum of radii to another at any physics step (measured 1.09)."""
    sim, rows = curly_first_stroke
    assert rows[0]["entanglement"] > 0.95 * sim.layout.n_links
    assert rows[1]["entanglement"] <= 0.5 * rows[0]["entanglement"]
    assert rows[1]["crossings"] == 0 and rows[1]["min_hair_hair"] >= 0.5


def _six_strokes(wig: str, seed: int) -> list[dict]:
    return repeated_strokes(BrushingSim(SceneConfig(wig=wig)), seed=seed, n_strokes=6)


@pytest.fixture(scope="module")
def curly_six_strokes() -> dict[int, list[dict]]:
    return {seed: _six_strokes("curly", seed) for seed in (0, 1, 2)}


@pytest.fixture(scope="module")
def coily_six_strokes() -> dict[int, list[dict]]:
    return {seed: _six_strokes("coily", seed) for seed in (0, 1, 2)}


@pytest.mark.slow
@pytest.mark.parametrize("wig", ["curly", "coily"])
def test_fig_3_6_full_strokes_detangle(curly_six_strokes, coily_six_strokes, wig: str):
    """Fig. 3.6(i) on curly and coily, seeds 0–2: six full strokes without abort leave at most 30 % of the
    entanglement (``hairbrush repeat --wigs curly,coily --seeds 3``; measured curly 0.30 / 0.24 / 0.26, coily
    0.25 / 0.27 / 0.22) and no strand crosses another."""
    series = curly_six_strokes if wig == "curly" else coily_six_strokes
    for rows in series.values():
        assert all(r["crossings"] == 0 and not r["diverged"] for r in rows[1:])
        assert rows[-1]["entanglement"] <= 0.3 * rows[0]["entanglement"]


@pytest.mark.slow
def test_fig_3_6_coily_force_falls_from_the_first_stroke(coily_six_strokes):
    """On coily every later full stroke reads less than the first (measured 13.0–14.2 N first, 4.0–5.4 N last)."""
    for rows in coily_six_strokes.values():
        forces = [r["max_force"] for r in rows[1:]]
        assert max(forces[1:]) < forces[0], forces


def _assert_no_pass_through(rows: list[dict]) -> None:
    """Every stroke of a series: no strand crossed another, none diverged, no strand came closer than half its
    diameter to itself (rows[0] is the untouched wig)."""
    assert all(r["crossings"] == 0 and not r["diverged"] and r["min_self"] >= 0.5 for r in rows[1:])


def _assert_falls_from_the_first_and_plateaus(series: dict[int, list[dict]]) -> None:
    """Fig. 3.6(i)'s shape on every series: every later stroke reads less than the first, and eq. 3.4
    (|Δf_max| < 0.4 N) is met within the series."""
    for rows in series.values():
        forces = [r["max_force"] for r in rows[1:]]
        assert max(forces[1:]) < forces[0], forces
        assert plateau_stroke(forces) is not None, forces


def _assert_fig_3_6_whole(
    series: dict[tuple[str, int], list[dict]],
    *,
    left_at_most: float,
    below_threshold_ok: tuple[str, ...] = (),
) -> None:
    """Fig. 3.6(i) whole on every ``(wig, seed)`` series: the first full stroke reads ≥ F_T (except on the wigs
    ``below_threshold_ok``), every later one less, eq. 3.4 is met, ≤ ``left_at_most`` of the entanglement is left
    after the last stroke, and no strand crosses another or comes closer than half its diameter to itself."""
    _assert_falls_from_the_first_and_plateaus(dict(enumerate(series.values())))
    for (wig, _), rows in series.items():
        if wig not in below_threshold_ok:
            assert rows[1]["max_force"] >= PAIN_THRESHOLD, wig
        assert rows[-1]["entanglement"] <= left_at_most * rows[0]["entanglement"], wig
        _assert_no_pass_through(rows)


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="curly seed 0 jams late (27.8 and 24.6 N at strokes 5 and 6 after 3.7 N: the free ends of one pair hooked "
    "together over the middle tine and pulled straight) and seed 2's second stroke reads 10.9 N after 10.4; eq. 3.4 "
    "is met on curly seeds 1 and 2 only (docs/detangling.md)",
)
def test_fig_3_6_curly_force_falls_and_plateaus(curly_six_strokes):
    """Fig. 3.6(i): every later stroke reads less than the first, and eq. 3.4 (|Δf_max| < 0.4 N) is met within six
    full strokes, on every curly seed."""
    _assert_falls_from_the_first_and_plateaus(curly_six_strokes)


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


@pytest.fixture(scope="module")
def coily_six_strokes_v1() -> dict[int, list[dict]]:
    from hairbrush_env.physics import get_physics

    v1 = get_physics("v1")
    return {
        s: repeated_strokes(BrushingSim(v1.scene_config("coily")), seed=s, n_strokes=6) for s in (0, 1, 2)
    }


@pytest.mark.slow
def test_fig_3_6_coily_under_v1_physics(coily_six_strokes_v1):
    """Fig. 3.6(i) under ``HairBrush-v1``'s physics (self-colliding strands, friction 0.15, soft comb), coily, seeds
    0–2 (``hairbrush repeat --physics v1 --wigs coily``): the first full stroke reads above F_T (measured 11.1 / 11.3
    / 11.5 N) and the second falls (6.2 / 4.4 / 4.5 N), six strokes leave ≤ 30 % of the entanglement (0.24 / 0.26 /
    0.28), and no strand crosses another or comes closer than half its diameter to itself (min 0.95)."""
    for rows in coily_six_strokes_v1.values():
        forces = [r["max_force"] for r in rows[1:]]
        assert forces[0] >= PAIN_THRESHOLD and forces[1] < forces[0], forces
        assert rows[-1]["entanglement"] <= 0.3 * rows[0]["entanglement"]
        _assert_no_pass_through(rows)


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="coily seed 2 under v1 jams in its fifth stroke (11.5 4.5 8.4 6.8 14.4 7.4 N) and never meets eq. 3.4; "
    "seeds 0 and 1 plateau (docs/detangling.md, *HairBrush-v1*)",
)
def test_fig_3_6_coily_under_v1_force_falls_and_plateaus(coily_six_strokes_v1):
    """Fig. 3.6(i) under v1: every later stroke reads less than the first, and eq. 3.4 is met within six strokes,
    on every coily seed."""
    _assert_falls_from_the_first_and_plateaus(coily_six_strokes_v1)


def _six_strokes_under(version: str, wig: str, seed: int) -> list[dict]:
    from hairbrush_env.physics import get_physics

    return repeated_strokes(BrushingSim(get_physics(version).scene_config(wig)), seed=seed, n_strokes=6)


def _series_under(version: str, wigs: tuple[str, ...]) -> dict[tuple[str, int], list[dict]]:
    """Fig. 3.6(i)'s series under ``version``: six full strokes on each of ``wigs``, seeds 0–2."""
    return {(w, s): _six_strokes_under(version, w, s) for w in wigs for s in (0, 1, 2)}


def _assert_two_strokes_comb_out(
    version: str, wig: str, *, first_at_least: float, second_below: float, left_at_most: float
) -> None:
    """Fig. 3.6(i) reduced to two full strokes on ``wig`` seed 0 under ``version``: the first reads ≥
    ``first_at_least``, the second < ``second_below`` × the first, ≤ ``left_at_most`` of the entanglement is left, and
    no strand crosses another or comes closer than half its diameter to itself."""
    from hairbrush_env.physics import get_physics

    rows = repeated_strokes(BrushingSim(get_physics(version).scene_config(wig)), seed=0, n_strokes=2)
    first, second = rows[1]["max_force"], rows[2]["max_force"]
    assert first >= first_at_least and second < second_below * first, (first, second)
    assert rows[-1]["entanglement"] <= left_at_most * rows[0]["entanglement"]
    _assert_no_pass_through(rows)


@pytest.fixture(scope="module")
def six_strokes_v2() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v2", ("curly", "coily"))


@pytest.mark.slow
def test_fig_3_6_curly_under_v2_reduced():
    """Fig. 3.6(i) under ``HairBrush-v2``'s physics, reduced to two full strokes on curly seed 0: the first reads
    near F_T (measured 10.2 N), the second less than half of it (3.6 N), two strokes leave ≤ 40 % of the
    entanglement (0.32), and no strand crosses another or comes closer than half its diameter to itself."""
    _assert_two_strokes_comb_out(
        "v2", "curly", first_at_least=0.8 * PAIN_THRESHOLD, second_below=0.5, left_at_most=0.4
    )


@pytest.mark.slow
def test_fig_3_6_under_v2_physics(six_strokes_v2):
    """Fig. 3.6(i) under v2 (``hairbrush repeat --physics v2 --wigs curly,coily --seeds 3``), six full strokes per
    series: the first reads 9.2–10.8 N, every series ends at ≤ 35 % of its entanglement (measured curly 0.29 /
    0.31 / 0.33, coily 0.23 / 0.27 / 0.26; the thesis's ≤ 30 % holds on four of six), the last two strokes read
    under half the first (curly seed 1's fourth reads 8.9 N after 9.2), and no strand crosses another or comes
    closer than half its diameter to itself (min 0.83)."""
    for rows in six_strokes_v2.values():
        forces = [r["max_force"] for r in rows[1:]]
        assert forces[0] >= 0.8 * PAIN_THRESHOLD and max(forces[4:]) < 0.5 * forces[0], forces
        assert rows[-1]["entanglement"] <= 0.35 * rows[0]["entanglement"]
        _assert_no_pass_through(rows)


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="under v2 curly seed 1 reads 8.9 N in its fourth stroke and never meets eq. 3.4, coily seed 2 reads 11.6 N "
    "in its second after 9.9; the other four series fall from the first stroke and plateau (docs/detangling.md, "
    "*HairBrush-v2*)",
)
def test_fig_3_6_under_v2_force_falls_and_plateaus(six_strokes_v2):
    """Fig. 3.6(i) under v2: every later stroke reads less than the first, and eq. 3.4 is met within six strokes, on
    every curly and coily seed."""
    _assert_falls_from_the_first_and_plateaus(dict(enumerate(six_strokes_v2.values())))


@pytest.mark.slow
def test_fig_3_6_curly_under_v3_reduced():
    """Fig. 3.6(i) under ``HairBrush-v3`` (pairs only), reduced to two full strokes on curly seed 0: the first reads
    above F_T (measured 11.4 N), the second much less (5.5 N), two strokes leave ≤ 30 % of the entanglement (0.23;
    v2 with its triples: 0.32), and no strand crosses another or comes closer than half its diameter to itself."""
    _assert_two_strokes_comb_out(
        "v3", "curly", first_at_least=PAIN_THRESHOLD, second_below=0.6, left_at_most=0.3
    )


@pytest.fixture(scope="module")
def six_strokes_v3() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v3", ("curly", "coily"))


@pytest.mark.slow
def test_fig_3_6_under_v3_physics(six_strokes_v3):
    """Fig. 3.6(i) whole under v3 (``hairbrush repeat --physics v3 --wigs curly,coily --seeds 3``), on every series:
    every later stroke reads less than the first (first 8.6–12.4 N), eq. 3.4 is met within six strokes (at strokes
    3–6), six strokes leave ≤ 30 % of the entanglement (measured 0.16–0.19), and no strand crosses another or comes
    closer than half its diameter to itself (min 1.21)."""
    _assert_falls_from_the_first_and_plateaus(dict(enumerate(six_strokes_v3.values())))
    for rows in six_strokes_v3.values():
        assert rows[-1]["entanglement"] <= 0.3 * rows[0]["entanglement"]
        _assert_no_pass_through(rows)


@pytest.mark.slow
def test_fig_3_6_curly_under_v5_reduced():
    """Fig. 3.6(i) under ``HairBrush-v5`` (v4 with 12 mm of straight hair below the roots), reduced to two full strokes
    on curly seed 0: the first reads near F_T (measured 10.5 N), the second much less (4.4 N), two strokes leave
    ≤ 30 % of the entanglement (0.15; v4: 0.25), and no strand crosses another or comes closer than half its
    diameter to itself."""
    _assert_two_strokes_comb_out(
        "v5", "curly", first_at_least=0.9 * PAIN_THRESHOLD, second_below=0.6, left_at_most=0.3
    )


@pytest.fixture(scope="module")
def six_strokes_v5() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v5", ("curly", "coily"))


@pytest.mark.slow
def test_fig_3_6_under_v5_physics(six_strokes_v5):
    """Fig. 3.6(i) under v5 (``hairbrush repeat --physics v5 --wigs curly,coily --seeds 3``): on every series six full
    strokes leave ≤ 30 % of the entanglement (measured curly 0.08 / 0.09 / 0.07, coily 0.09 / 0.08 / 0.07; v4's
    coily 0.40–0.44) and no strand crosses another or comes closer than half its diameter to itself. On curly every
    later stroke reads less than the first (first 8.8–10.5 N) and eq. 3.4 is met within the six strokes."""
    for (wig, _), rows in six_strokes_v5.items():
        forces = [r["max_force"] for r in rows[1:]]
        assert rows[-1]["entanglement"] <= 0.3 * rows[0]["entanglement"], (wig, forces)
        _assert_no_pass_through(rows)
    _assert_falls_from_the_first_and_plateaus({k: v for k, v in six_strokes_v5.items() if k[0] == "curly"})


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="coily's second full stroke reads more than its first on seeds 0 and 2 (11.1 and 11.0 N after 9.4 and "
    "9.2): the first stroke unwinds every pair and the second winds 3–4 again; seed 1 meets no plateau within six "
    "(docs/detangling.md, *HairBrush-v5*)",
)
def test_fig_3_6_coily_force_falls_under_v5(six_strokes_v5):
    """Fig. 3.6(i)'s shape on coily under v5: every later stroke reads less than the first, and eq. 3.4 is met."""
    _assert_falls_from_the_first_and_plateaus({k: v for k, v in six_strokes_v5.items() if k[0] == "coily"})


@pytest.mark.slow
def test_fig_3_6_coily_under_v6_reduced():
    """Fig. 3.6(i) under ``HairBrush-v6`` (v5 with a pair's strands resting 2R apart across the tines), reduced to two
    full strokes on coily seed 0: the first reads above F_T (measured 11.4 N), the second far less (2.8 N; under v5
    it read more than the first, 11.1 after 9.4 N, its strands left on one axis), two strokes leave ≤ 15 % of the
    entanglement (0.08), and no strand crosses another or comes closer than half its diameter to itself."""
    _assert_two_strokes_comb_out(
        "v6", "coily", first_at_least=PAIN_THRESHOLD, second_below=0.5, left_at_most=0.15
    )


@pytest.fixture(scope="module")
def six_strokes_v6() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v6", ("curly", "coily"))


@pytest.mark.slow
def test_fig_3_6_under_v6_physics(six_strokes_v6):
    """Fig. 3.6(i) whole under v6 (``hairbrush repeat --physics v6 --wigs curly,coily --seeds 3``), on all six series:
    the first full stroke reads above F_T (measured 11.4–13.2 N), every later one less, eq. 3.4 is met within six
    strokes, six strokes leave ≤ 10 % of the entanglement (measured 0.04–0.07), and no strand crosses another or
    comes closer than half its diameter to itself."""
    _assert_fig_3_6_whole(six_strokes_v6, left_at_most=0.1)


@pytest.mark.slow
def test_fig_3_6_coily_under_v7_reduced():
    """Fig. 3.6(i) under ``HairBrush-v7`` (coily's curls at R = 9 mm, rest shapes turned by 2π/3), reduced to two
    full strokes on coily seed 0: the first reads above F_T (measured 18.87 N), the second far less (5.64 N; with
    v6's π/2 at 9 mm, 17.18 N: the coils reached no tine and the first stroke gathered each pair onto the middle
    one), two strokes leave ≤ 15 % of the entanglement (0.04), and no strand crosses another or comes closer than
    half its diameter to itself."""
    _assert_two_strokes_comb_out(
        "v7", "coily", first_at_least=PAIN_THRESHOLD, second_below=0.5, left_at_most=0.15
    )


@pytest.fixture(scope="module")
def six_strokes_v7() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v7", ("coily", "tight_curl"))


@pytest.mark.slow
def test_fig_3_6_under_v7_physics(six_strokes_v7):
    """Fig. 3.6(i) on coily and tight_curl under v7 (``hairbrush repeat --physics v7 --wigs coily,tight_curl --seeds
    3``; curly is v6's wig): the first full stroke reads above F_T (measured 18.9 N on coily, 13.4–14.1 N on
    tight_curl), every later one less (≤ 5.6 N), eq. 3.4 is met within six strokes (by stroke 3–5), six strokes leave
    ≤ 10 % of the entanglement (0.02–0.05), and no strand crosses another or comes closer than half its diameter to
    itself."""
    _assert_fig_3_6_whole(six_strokes_v7, left_at_most=0.1)


def test_fig_3_6_tight_curl_under_v8_reduced():
    """Fig. 3.6(i) under ``HairBrush-v8`` (tines of the hair's friction 0.15), reduced to two full strokes on
    tight_curl seed 0: the first reads above F_T (measured 11.8 N), the second far less (2.6 N), two strokes leave
    ≤ 15 % of the entanglement (0.03), and no strand crosses another or comes closer than half its diameter to
    itself."""
    _assert_two_strokes_comb_out(
        "v8", "tight_curl", first_at_least=PAIN_THRESHOLD, second_below=0.5, left_at_most=0.15
    )


@pytest.fixture(scope="module")
def six_strokes_v8() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v8", ("curly", "tight_curl", "coily"))


@pytest.mark.slow
def test_fig_3_6_under_v8_physics(six_strokes_v8):
    """Fig. 3.6(i) under v8 (``hairbrush repeat --physics v8 --wigs curly,coily,tight_curl --seeds 3``), on all nine
    series: every later full stroke reads less than the first (first: curly 9.7–9.8, tight_curl 11.8–12.0, coily
    14.3 N; later ≤ 3.4 N), eq. 3.4 is met within six strokes (by stroke 3–4), six strokes leave ≤ 10 % of the
    entanglement (0.03–0.06), and no strand crosses another or comes closer than half its diameter to itself. The
    first strokes on tight_curl and coily read above F_T; curly's just below it (docs/detangling.md, *HairBrush-v8*)."""
    _assert_fig_3_6_whole(six_strokes_v8, left_at_most=0.1, below_threshold_ok=("curly",))


@pytest.fixture(scope="module")
def six_strokes_v9() -> dict[tuple[str, int], list[dict]]:
    return _series_under("v9", ("curly", "tight_curl", "coily"))


@pytest.mark.slow
def test_fig_3_6_under_v9_physics(six_strokes_v9):
    """Fig. 3.6(i) under v9 (``hairbrush repeat --physics v9 --wigs W --seeds 3``), on all nine series as under v8:
    every later full stroke reads less than the first (first: curly 9.0–9.9, tight_curl 11.8–11.9, coily 14.2–14.3 N;
    later ≤ 3.5 N), eq. 3.4 is met within six strokes (by stroke 3–5), six strokes leave ≤ 10 % of the entanglement
    (0.02–0.08), and no strand crosses another or comes closer than half its diameter to itself
    (docs/detangling.md, *HairBrush-v9*)."""
    _assert_fig_3_6_whole(six_strokes_v9, left_at_most=0.1, below_threshold_ok=("curly",))
