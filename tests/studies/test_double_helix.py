"""Double-helix combing (thesis chapter 2): setup validation, geometry, eq. 2.8 cost, and reduced physics runs.

Default-suite runs use short (6 cm), coarse (8 edges per pitch) helices; the full-size study (15 cm, 10 edges per
pitch) is in docs/double_helix.md and in the ``slow`` tests.
"""

from __future__ import annotations

from itertools import pairwise

import numpy as np
import pytest

from hairbrush_env.studies.double_helix import (
    KINK_ANGLE,
    CombingResult,
    CombingSetup,
    braid_bend,
    breakthroughs,
    combing_cost,
    jam_metrics,
    optimal_q,
    replace_setup,
    run_combing,
)
from hairbrush_env.studies.double_helix.model import bulge, strand_points
from hairbrush_env.studies.double_helix.run import passages
from hairbrush_env.topology import linking_number

REDUCED = dict(height=0.06, edges_per_pitch=8, samples=60, settle_time=0.2)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("P_over_r", -1.0),
        ("R_over_r", 0.9),
        ("poisson", 0.5),
        ("edges_per_pitch", 2),
        ("speed", 0.0),
        ("q", 30.0),
        ("contact_timeconst", 0.003),  # < 2 × the 2 ms step
    ],
)
def test_setup_rejects_bad_fields(field, value):
    with pytest.raises(ValueError, match=field):
        CombingSetup(**{field: value})


def test_replace_setup_parses_cli_strings():
    s = replace_setup(CombingSetup(), P_over_r="18", q="none", edges_per_pitch="6")
    assert s.P_over_r == 18.0 and s.q is None and s.edges_per_pitch == 6
    assert replace_setup(s, q="4").q_effective == pytest.approx(4.0)
    with pytest.raises(ValueError, match="nope"):
        replace_setup(s, nope="1")


def test_insertion_near_the_clamp_traps_about_half_a_link():
    """``q=clamp`` (the thesis's simulated insertion "close to the clamped end"): just over half a pitch stays
    above the tine, so about half a link is trapped there (lk_above) and the rest can be combed out."""
    base = CombingSetup(P_over_r=36, **REDUCED)
    s = replace_setup(base, q="clamp")
    assert s.q == pytest.approx(s.height / s.pitch - 0.51)
    assert replace_setup(base, q="clamp", P_over_r=24).q == pytest.approx(
        base.height / (24 * base.radius) - 0.51
    )
    res = run_combing(s)
    assert res.lk_above == pytest.approx(0.5, abs=0.15)
    assert res.lk_end < res.lk_above + 0.1 * res.lk0  # all but ≤ 10 % of Lk0 of the combable link leaves


def test_initial_geometry_and_link():
    s = CombingSetup()
    a, b = strand_points(s)
    assert a[0, 2] == 0.0 and a[-1, 2] == pytest.approx(-s.height)
    np.testing.assert_allclose(np.linalg.norm(a - b, axis=1), 2 * s.helix_radius, rtol=1e-12)
    # one link per pitch: Lk0 ≈ h/P (open-curve ends lose a fraction of a turn)
    assert linking_number(a, b, closed=False) == pytest.approx(s.turns, abs=0.2)
    # at the insertion depth the strands lie on ±x, i.e. across the tine (along y)
    k = int(np.argmin(np.abs(a[:, 2] + s.insertion_depth)))
    assert abs(a[k, 1]) < 0.5 * s.helix_radius and a[k, 0] > 0
    # the insertion bump leaves the tine (radius t) clear of both strands everywhere
    for p in (a, b):
        q = p + bulge(p, s)
        dist = np.hypot(q[:, 0], q[:, 2] + s.insertion_depth)
        assert dist.min() >= s.tine_radius + s.radius


def test_cost_eq_2_8():
    q = np.array([2.0, 4.0, 8.0, 12.0])
    fmax = np.array([5.0, 9.0, 20.0, 40.0])
    np.testing.assert_allclose(combing_cost(fmax, q, 1.0), fmax)
    np.testing.assert_allclose(combing_cost(fmax, q, 0.0), 25.0 / q)
    np.testing.assert_allclose(combing_cost(fmax, q, 0.5), 0.5 * fmax + 12.5 / q)
    assert optimal_q(q, fmax, 1.0) == 2.0  # pain only: short strokes
    assert optimal_q(q, fmax, 0.0) == 12.0  # time only: long strokes
    with pytest.raises(ValueError, match="gamma"):
        combing_cost(fmax, q, 1.5)


def test_jam_metrics_on_synthetic_curves():
    x = np.linspace(0, 1.05, 200)
    plateau = np.minimum(x / 0.2, 1.0) * (x < 0.95)  # rise, level off, drop at the free end
    jam = plateau + 2.0 * np.exp(-(((x - 0.4) / 0.05) ** 2))  # peak, then break-through
    assert not jam_metrics(x, plateau)[0]
    assert jam_metrics(x, jam)[0]


def test_breakthroughs_pair_each_force_drop_with_the_braid_bend():
    """The jam cycle of thesis §2.4: a peak at a kink, then the drop as the tine breaks through. Each drop of the
    smoothed force by ≥ 20 % is found once, with the largest bend around it; NaN bend (not measured) is no kink."""
    x = np.linspace(0, 1.05, 211)
    level = np.minimum(x / 0.2, 1.0) * (x < 0.95)  # rise, level off, drop at the free end
    bump = lambda c: 1.0 * np.exp(-(((x - c) / 0.03) ** 2))  # noqa: E731
    f = level + bump(0.35) + bump(0.65)  # two jam peaks of twice the level
    bend = np.full(x.size, 5.0)
    bend[np.abs(x - 0.36) < 0.02] = 45.0  # a kink at the first break-through only
    bend[x > 0.85] = np.nan  # fewer than 3 pitches below the tine: not measured
    found = breakthroughs(x, f, bend)
    np.testing.assert_allclose([b.x_peak for b in found], [0.35, 0.65, 0.93], atol=0.02)
    assert [b.kinked for b in found] == [True, False, False]
    assert found[0].bend == 45.0 and found[1].bend == 5.0 and np.isnan(found[2].bend)
    assert all(b.f_peak >= 1.25 * b.f_drop for b in found)
    # a smooth plateau has no break-through until the exit; ±10 % ripples are not break-throughs either
    ripples = breakthroughs(x, level * (1 + 0.1 * np.sin(60 * x)), bend)
    assert len(ripples) == 1 and ripples[0].x_drop > 0.85  # only the exit,
    assert np.isnan(ripples[0].bend)  # where the bend is not measured
    with pytest.raises(ValueError, match="bend"):
        breakthroughs(x, f, bend[:-1])
    with pytest.raises(ValueError, match="ratio"):
        breakthroughs(x, f, bend, ratio=1.0)


def test_passage_of_one_strand_through_another_is_counted_once():
    """The topology check: a strand pushed through another makes their open Gauss integral jump by exactly 1;
    a strand that slides past the other's end changes it continuously and is not counted."""
    b = np.column_stack([np.zeros(41), np.linspace(-0.02, 0.02, 41), np.zeros(41)])  # along ŷ at z = 0

    def a_at(z: float, x0: float = 0.0) -> np.ndarray:
        return np.column_stack([np.linspace(-0.02, 0.02, 41) + x0, np.zeros(41), np.full(41, z)])

    def count(path) -> int:
        lks = [linking_number(a, b, closed=False) for a in path]
        return int(sum(passages(p, n) for p, n in pairwise(lks)))

    through = [a_at(z) for z in np.linspace(4e-4, -4e-4, 8)]  # ~0.1 mm per check, through b at z = 0
    assert count(through) == 1
    # the same z sweep but 3 cm to the side: a passes beside b's end, no crossing
    beside = [a_at(z, x0=0.0) + np.array([0.0, 0.03, 0.0]) for z in np.linspace(4e-4, -4e-4, 8)]
    assert count(beside) == 0
    assert passages(np.array([0.1, -0.4, 2.0]), np.array([-0.95, -0.1, -0.1])).tolist() == [1, 0, 2]


def _fold_below(points: np.ndarray, z_pivot: float, angle_deg: float) -> np.ndarray:
    """Rotate the part of a strand below ``z_pivot`` about the x axis through (0, 0, z_pivot)."""
    a = np.radians(angle_deg)
    rot = np.array([[1.0, 0.0, 0.0], [0.0, np.cos(a), -np.sin(a)], [0.0, np.sin(a), np.cos(a)]])
    pivot = np.array([0.0, 0.0, z_pivot])
    out = points.copy()
    low = points[:, 2] < z_pivot
    out[low] = pivot + (points[low] - pivot) @ rot.T
    return out


def test_braid_bend_measures_the_fold_of_the_braid_below_the_tine():
    """The kink measure on exact geometry: a straight hanging double helix bends 0°, a braid folded by 40° / 70°
    below the tine bends 40° / 70°; splayed free ends (last pitch) and folds with < 3 pitches below do not count."""
    s = CombingSetup(P_over_r=24)
    a, b = strand_points(s)
    ppp = s.edges_per_pitch
    z_tine = -0.04
    straight = np.stack([a, b])[None]
    assert braid_bend(straight, z_tine, ppp)[0] < 1.0

    z_pivot = z_tine - 2 * s.pitch
    for angle in (40.0, 70.0):
        folded = np.stack([_fold_below(a, z_pivot, angle), _fold_below(b, z_pivot, angle)])[None]
        assert braid_bend(folded, z_tine, ppp)[0] == pytest.approx(angle, abs=2.0)
    assert KINK_ANGLE == pytest.approx(30.0)

    # free ends splayed sideways over the last pitch: untwisting, not a bend of the braid
    splay = np.linspace(0.0, 1.0, ppp + 1)[:, None] * np.array([0.0, 0.02, 0.0])
    a_s, b_s = a.copy(), b.copy()
    a_s[-ppp - 1 :] += splay
    b_s[-ppp - 1 :] += 0.5 * splay
    assert braid_bend(np.stack([a_s, b_s])[None], z_tine, ppp)[0] < 1.0

    # fewer than 3 pitches below the tine: not measured
    z_low = float(a[-1, 2]) + 2.5 * s.pitch
    assert np.isnan(braid_bend(straight, z_low, ppp)[0])
    # several frames at once, one tine height each
    both = np.concatenate([straight, straight])
    out = braid_bend(both, np.array([z_tine, z_low]), ppp)
    assert out[0] < 1.0 and np.isnan(out[1])

    with pytest.raises(ValueError, match="frames"):
        braid_bend(np.stack([a, b]), z_tine, ppp)
    with pytest.raises(ValueError, match="points_per_pitch"):
        braid_bend(straight, z_tine, 1)


@pytest.fixture(scope="module")
def reduced_run() -> CombingResult:
    return run_combing(CombingSetup(P_over_r=24, **REDUCED))


def test_reduced_run_topology(reduced_run):
    r = reduced_run
    s = r.setup
    assert r.lk0 == pytest.approx(s.turns, rel=0.06)  # Lk_initial ≈ number of shared turns
    assert r.max_stretch < 0.01  # inextensible
    # link leaves only through the free end: no strand passed through the other strand or the tine
    assert r.strand_crossings == 0 and r.tine_crossings == 0
    # link ahead of the tine is expelled: ≤ 10 % of the combable link is left (thesis claim 3)
    assert abs(r.combed_lk_end_fraction) <= 0.10
    # the link above the insertion point is trapped by the long tine
    assert r.lk_end == pytest.approx(r.lk_above, abs=0.1 * r.lk0)
    # overwinding between tine and free end, underwinding behind it (Fig. 2.2e)
    x_snap = 0.4
    sgrid, dl = r.snapshots[x_snap]
    k = int(np.argmin(np.abs(r.x - x_snap)))
    depth_tine = s.insertion_depth + r.d[k]
    s_tine_frac = depth_tine / s.height
    frac = sgrid / sgrid[-1]
    ahead = (frac > s_tine_frac + 0.05) & (frac < 0.95)
    behind = (frac > 0.05) & (frac < s_tine_frac - 0.05)
    assert np.median(dl[ahead]) > 0.0
    assert np.median(dl[behind]) < 0.0
    # link current grows in magnitude, then plateaus (Fig. 2.8) until the tine breaks out at the free end, where the
    # last links leave at once (the force drops to 0 there; D counts on to the last light touch of the free ends)
    release = r.x[np.flatnonzero(r.f >= 0.5 * r.f_max)[-1]]
    assert release > 0.45
    early = np.abs(r.current[(r.x > 0.0) & (r.x < 0.06)]).mean()
    # the current is a 5-sample moving average (run_combing), so the jump leaks ~3 samples (0.05 in x) before it
    late = np.abs(r.current[(r.x > 0.3) & (r.x < release - 0.1)])
    assert late.mean() > 2 * early
    assert late.std() < 0.2 * late.mean()


def test_reduced_run_force_and_love(reduced_run):
    r = reduced_run
    assert r.f_max > 0 and 0.0 < r.D <= 1.2 * (r.setup.height - r.setup.insertion_depth)
    assert np.all(np.isfinite(r.f))
    # Love's no-slip single-helix curve starts at 0 and overestimates the combing force (thesis appendix)
    early = (r.x > 0.0) & np.isfinite(r.love_f)
    assert r.love_f[0] == pytest.approx(0.0, abs=1e-9)
    assert np.all(r.love_f[early][1:] > r.f[early][1:])
    # round trip through the cache format
    back = CombingResult.from_dict(r.to_dict())
    assert back.f_max == r.f_max and back.setup == r.setup
    assert (back.strand_crossings, back.tine_crossings) == (r.strand_crossings, r.tine_crossings)
    np.testing.assert_array_equal(back.lk, r.lk)
    np.testing.assert_array_equal(back.bend, r.bend)  # NaN where not measured survives (as JSON null)
    assert back.kinked == r.kinked
    assert (back.kink_jams, back.kink_free_drops) == (r.kink_jams, r.kink_free_drops)
    # results cached before the bend measure: NaN (not measured), never "kinked"
    old = r.to_dict()
    del old["bend"]
    legacy = CombingResult.from_dict(old)
    assert np.isnan(legacy.bend_max) and not legacy.kinked
    assert legacy.kink_jams == 0 and legacy.kink_free_drops == 0 and not legacy.jammed_by_kink


def test_bend_max_ignores_the_release_and_what_follows_a_passage(reduced_run):
    """``bend_max`` is taken within the stroke (x ≤ 1) and before the first strand passage."""
    from dataclasses import replace

    r = reduced_run
    n = r.x.size
    bend = np.full(n, 5.0)
    k_mid = n // 3
    bend[k_mid + 1] = 80.0  # after the passage below
    bend[-1] = 85.0  # beyond the stroke when x > 1 there
    fake = replace(r, bend=bend, crossing_d=(float(r.d[k_mid]),))
    assert fake.bend_max == pytest.approx(5.0) and not fake.kinked
    assert replace(r, bend=bend).bend_max == pytest.approx(80.0 if r.x[-1] > 1.0 else 85.0)
    assert replace(r, bend=bend).kinked


def test_reduced_pitch_trend():
    """f_max falls as P/r grows (claim 1), on short coarse helices."""
    tight = run_combing(CombingSetup(P_over_r=18, **REDUCED))
    loose = run_combing(CombingSetup(P_over_r=48, **REDUCED))
    assert tight.f_max > 2.0 * loose.f_max


def test_quasi_static_speed_independence():
    """At the default 5 mm/s the combing force is quasi-static: halving the speed changes f_max by < 5 %.

    (At the former 20 mm/s default, halving lowered f_max by 19 %: 3.77 -> 3.05 on this helix.)
    """
    base = CombingSetup(P_over_r=36, **REDUCED)
    fast = run_combing(base)
    slow = run_combing(replace_setup(base, speed=base.speed / 2))
    assert slow.f_max == pytest.approx(fast.f_max, rel=0.05)


@pytest.fixture(scope="module")
def full_size_runs() -> dict[tuple[float, float], CombingResult]:
    """Full-size (15 cm, 10 edges/pitch) helices at mid-height insertion, keyed by (P/r, R/r)."""
    keys = [(18, 1), (48, 1), (24, 1), (24, 3)]
    return {k: run_combing(CombingSetup(P_over_r=k[0], R_over_r=k[1])) for k in keys}


@pytest.mark.slow
def test_full_size_claim_1(full_size_runs):
    """Claim 1 on full-size helices: f_max falls as P/r grows (18 -> 48) and as R/r grows (1 -> 3)."""
    res = full_size_runs
    assert res[18, 1].f_max > 5 * res[48, 1].f_max  # measured 34.5 vs 3.25
    assert res[24, 1].f_max > 1.2 * res[24, 3].f_max  # measured 18.9 vs 13.7


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    reason="known difference (docs/double_helix.md): quasi-statically (5 mm/s) the force-only flag sees no jam of "
    "the tight "
    "P/r = 18 helix at mid-height insertion (force rises to a plateau, peak/level 1.01); claim 2 holds by the "
    "thesis's kink jams near the clamp (test_full_size_claim_2_tight_helices_kink_jam_near_the_clamp)",
)
def test_full_size_claim_2_tight_helices_jam(full_size_runs):
    res = full_size_runs
    assert res[18, 1].jammed and not res[48, 1].jammed


@pytest.mark.slow
def test_full_size_tight_helices_bend_below_the_tine(full_size_runs):
    """The kink side of claim 2 (Fig. 2.2a): below the tine the tight helix's braid bends away from the vertical,
    the loose one hangs straight. Measured (docs/double_helix.md): 16.5° for P/r = 18, 0.0° for P/r = 48 (no jam in
    the force
    for either, and 16.5° stays below the 30° kink threshold)."""
    res = full_size_runs
    assert res[18, 1].bend_max > 10.0
    assert res[48, 1].bend_max < 2.0


@pytest.mark.slow
def test_full_size_claim_4_long_strokes_kink():
    """Claim 4 by the thesis's kink criterion (Fig. 2.4: "below a certain link threshold, combing finishes without
    kink formation"): 4 pitches from the free end the braid stays straight, 12 pitches away it kinks and the tine
    breaks through at the kink (a kink jam, §2.4).
    Measured (docs/double_helix.md): 1.5° and no break-through at q = 4; 38.9° and one kink jam at q = 12 (before its
    strand
    passage at x = 0.58)."""
    base = CombingSetup(P_over_r=24)
    short = run_combing(replace_setup(base, q=4))
    long = run_combing(replace_setup(base, q=12))
    assert short.bend_max < 5.0 and not short.kinked and short.kink_jams == 0
    assert long.kinked and long.bend_max >= KINK_ANGLE and long.jammed_by_kink


@pytest.mark.slow
def test_full_size_claim_4_tall_helix_jams_only_far_from_the_free_end():
    """Claim 4 over the thesis's q range (Fig. 2.4 goes to q = 25), on a 30 cm helix (29.4 pitches): a short stroke
    neither kinks nor jams, the longest goes through kink jams and the force-only flag sees them too.
    Measured (docs/double_helix.md): q = 6 bend 1.3°, peak/level 0.97; q = 25 bend 61.6°, 2 kink jams, peak/level
    1.32."""
    base = CombingSetup(P_over_r=24, height=0.3)
    short = run_combing(replace_setup(base, q=6))
    long = run_combing(replace_setup(base, q=25))
    assert short.bend_max < 5.0 and short.kink_jams == 0 and not short.jammed
    assert long.jammed_by_kink and long.jammed and long.strand_crossings == 0


@pytest.fixture(scope="module")
def clamp_runs() -> dict[float, CombingResult]:
    """Full-size helices (R/r = 1) with the thesis's insertion near the clamp, keyed by P/r."""
    return {p: run_combing(replace_setup(CombingSetup(P_over_r=p), q="clamp")) for p in (24, 36, 48)}


@pytest.mark.slow
def test_full_size_claim_2_tight_helices_kink_jam_near_the_clamp(clamp_runs):
    """Claim 2 by the thesis's jam cycle (§2.4: a kink "accompanied by a peak in applied force", then "the tine
    breaks through and the force decreases"; loose helices never cross "the threshold needed for kinking"), with the
    tine inserted near the clamp as in the thesis's simulations. Measured (docs/double_helix.md): 4 kink jams at P/r
    = 24, none at
    P/r = 36 and 48 (whose force still drops 4 and 3 times, with the braid bent ≤ 12.5°)."""
    assert clamp_runs[24].jammed_by_kink and clamp_runs[24].kinked
    assert clamp_runs[36].kink_jams == 0 and clamp_runs[48].kink_jams == 0
    assert clamp_runs[48].bend_max < 10.0  # the loose braid hangs straight below the tine


@pytest.mark.slow
@pytest.mark.parametrize("p_over_r", [24, 36])
def test_full_size_claim_3_total_link_leaves(clamp_runs, p_over_r):
    """Claim 3 on full-size helices with the thesis's insertion near the clamp: total Lk ends at ≤ 10 % of Lk0.

    Measured (docs/double_helix.md): 14.4 % for P/r = 18 (one strand passage; 4.0 % with 4× stiffer contacts), 4.8 /
    7.3 / 9.97 %
    for P/r = 24 / 36 / 48; the two with margin and no passage are asserted here.
    """
    res = clamp_runs[p_over_r]
    assert res.strand_crossings == 0 and res.tine_crossings == 0  # the link left through the free end
    assert res.lk_above < 0.65  # about half a link is trapped between clamp and tine
    assert abs(res.lk_end_faithful) <= 0.10 * res.lk0
