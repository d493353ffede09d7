"""Single-stroke force studies (:mod:`hairbrush_env.stroke_study`): input checks, outputs, resume, Fig. 3.8."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np
import pytest

from hairbrush_env import stroke_study
from hairbrush_env.scene import BrushingSim


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"wigs": ["nope"]}, "wigs"),
        ({"wigs": []}, "wigs"),
        ({"brush_lengths": [1.5]}, "brush_lengths"),
        ({"brush_lengths": [float("nan")]}, "brush_lengths"),
        ({"speeds": [0.0]}, "speeds"),
        ({"speeds": []}, "speeds"),
        ({"seeds": []}, "seeds"),
    ],
)
def test_bad_input_names_the_argument(kwargs: dict, name: str) -> None:
    args = {"wigs": ["curly"], **kwargs}
    wigs = args.pop("wigs")
    with pytest.raises(ValueError, match=name):
        stroke_study.measure_strokes(wigs, progress=False, **args)


def test_outputs_and_resume(tmp_path, monkeypatch) -> None:
    rows = stroke_study.measure_strokes(
        ["curly"], brush_lengths=[0.2], speeds=[0.1], seeds=[0], out=tmp_path, progress=False
    )
    assert len(rows) == 1 and not rows[0]["diverged"]
    assert rows[0]["max_force"] >= 0.0 and rows[0]["sim_time"] > 0.0
    for name in ("strokes.csv", "summary.md", "force_vs_brush_length.png", "force_vs_speed.png"):
        assert (tmp_path / name).stat().st_size > 0
    assert stroke_study.read_strokes(tmp_path / "strokes.csv") == rows

    # A rerun finds every cell done and must not simulate again.
    def no_stroke(*args, **kwargs):
        raise AssertionError("resumed run simulated a finished cell")

    monkeypatch.setattr(BrushingSim, "stroke", no_stroke)
    again = stroke_study.measure_strokes(
        ["curly"], brush_lengths=[0.2], speeds=[0.1], seeds=[0], out=tmp_path, progress=False
    )
    assert again == rows


def test_summary_statistics() -> None:
    rows = [
        {"wig": "curly", "R_over_P": 0.5, "brush_length": 1.0, "speed": 0.1, "seed": s, "max_force": f,
         "sim_time": 1.0, "diverged": d}
        for s, f, d in ((0, 2.0, False), (1, 4.0, False), (2, 100.0, True))
    ]  # fmt: skip
    (entry,) = stroke_study.summarize(rows)
    assert entry["n"] == 2  # the diverged stroke is excluded
    assert entry["mean"] == pytest.approx(3.0)
    assert entry["std"] == pytest.approx(np.std([2.0, 4.0], ddof=1))


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="mass-scaled strands (WigConfig.mass_scale = 10) are not quasi-static at these speeds: curly at b_l 0.67 "
    "reads 4.77 / 5.15 / 6.76 / 8.98 N at 0.025 / 0.05 / 0.1 / 0.2 m/s (0.05 to 0.2: +74 %; hairbrush strokes "
    "--speeds, docs/detangling.md), against +12 to +23 % with the real mass",
)
def test_speed_changes_max_force_little(tmp_path) -> None:
    """Thesis Fig. 3.8: at a fixed brush length, a 4× change of brushing speed changes the mean max force little
    (here: by less than 25 % of the mean, or 1 N on nearly force-free straight hair)."""
    rows = stroke_study.measure_strokes(
        ["straight", "curly"], brush_lengths=[0.5], speeds=[0.05, 0.2], seeds=[0, 1, 2], progress=False
    )
    assert not any(r["diverged"] for r in rows)
    table = {(e["wig"], e["speed"]): e["mean"] for e in stroke_study.summarize(rows)}
    for wig in ("straight", "curly"):
        slow, fast = table[(wig, 0.05)], table[(wig, 0.2)]
        assert abs(slow - fast) <= max(1.0, 0.25 * 0.5 * (slow + fast)), (wig, slow, fast)


def _fig_3_7_grid(physics: str) -> dict[tuple[str, float], float]:
    """Mean max force per (preset, b_l) over seeds 0–2 at b_l 0.33, 0.67, 1 under ``physics`` (Fig. 3.7's grid)."""
    from hairbrush_env.executor import ExecutorConfig
    from hairbrush_env.hair import PRESETS

    return _mean_force(
        stroke_study.measure_strokes(
            list(PRESETS),
            brush_lengths=[0.33, 0.67, 1.0],
            seeds=[0, 1, 2],
            executor=ExecutorConfig(workers=2),
            progress=False,
            physics=physics,
        )
    )


def _fig_3_8_table(physics: str) -> dict[tuple[str, float, float], float]:
    """Mean max force per (wig, b_l, speed) over seeds 0–2 on curly and coily at b_l 0.67 and 1, 0.05 and 0.2 m/s
    under ``physics`` (Fig. 3.8's grid)."""
    from hairbrush_env.executor import ExecutorConfig

    rows = stroke_study.measure_strokes(
        ["curly", "coily"],
        brush_lengths=[0.67, 1.0],
        speeds=[0.05, 0.2],
        seeds=[0, 1, 2],
        executor=ExecutorConfig(workers=2),
        progress=False,
        physics=physics,
    )
    assert not any(r["diverged"] for r in rows)
    return {(e["wig"], e["brush_length"], e["speed"]): e["mean"] for e in stroke_study.summarize(rows)}


def _mean_force(rows: list[dict]) -> dict[tuple[str, float], float]:
    assert not any(r["diverged"] for r in rows)
    return {(e["wig"], e["brush_length"]): e["mean"] for e in stroke_study.summarize(rows)}


@pytest.mark.slow
def test_fig_3_7_under_v1_reduced() -> None:
    """Figs 3.6(ii) and 3.7 under ``HairBrush-v1``'s physics, reduced (seed 0): straight hair barely loads the soft
    comb (measured 0.0 N), and curly's full stroke reads more than its third (9.6 against 4.3 N) and more than
    straight's."""
    t = _mean_force(
        stroke_study.measure_strokes(
            ["straight", "curly"], brush_lengths=[0.33, 1.0], seeds=[0], progress=False, physics="v1"
        )
    )
    assert t[("straight", 1.0)] < 0.5
    assert t[("curly", 0.33)] < t[("curly", 1.0)]
    assert t[("curly", 1.0)] > t[("straight", 1.0)] + 2.0


@pytest.mark.slow
def test_fig_3_7_under_v1() -> None:
    """Fig. 3.7 under v1, mean max force over seeds 0–2, no abort (``hairbrush strokes --physics v1 --wigs all
    --brush-lengths 0.33,0.67,1 --seeds 3``): the force grows with b_l on every curled preset (Fig. 3.6(ii)), and at
    b_l = 1 with curliness, straight staying well below F_T and the curliest full stroke above it (measured 0.02 <
    4.82 < 5.30 < 9.40 < 10.92 < 11.29 N)."""
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.scene import PAIN_THRESHOLD

    t = _fig_3_7_grid("v1")
    for name in list(PRESETS)[1:]:
        assert t[(name, 0.33)] < t[(name, 0.67)] < t[(name, 1.0)], name
    full = np.array([t[(name, 1.0)] for name in PRESETS])
    assert np.all(np.diff(full) > 0), full
    assert full[0] < 0.5 and full[-1] > PAIN_THRESHOLD, full


@pytest.mark.slow
def test_fig_3_6_ii_under_v3_reduced() -> None:
    """Fig. 3.6(ii) under ``HairBrush-v3``'s physics, reduced (seed 0, no abort): a tight_curl stroke reads more the
    longer it is (measured 3.27 < 7.08 < 9.13 N at b_l 0.33 / 0.67 / 1), and straight hair barely loads the comb
    (0.01 N)."""
    t = _mean_force(
        stroke_study.measure_strokes(
            ["straight"], brush_lengths=[1.0], seeds=[0], progress=False, physics="v3"
        )
        + stroke_study.measure_strokes(
            ["tight_curl"], brush_lengths=[0.33, 0.67, 1.0], seeds=[0], progress=False, physics="v3"
        )
    )
    assert t[("straight", 1.0)] < 0.5
    assert t[("tight_curl", 0.33)] < t[("tight_curl", 0.67)] < t[("tight_curl", 1.0)]
    assert t[("tight_curl", 1.0)] > t[("straight", 1.0)] + 2.0


@pytest.fixture(scope="module")
def fig_3_7_v3() -> dict[tuple[str, float], float]:
    return _fig_3_7_grid("v3")


@pytest.mark.slow
def test_fig_3_6_ii_under_v3(fig_3_7_v3) -> None:
    """Figs 3.6(ii) and 3.7 under v3, mean max force over seeds 0–2, no abort (``hairbrush strokes --physics v3
    --wigs all --brush-lengths 0.33,0.67,1 --seeds 3``): the force grows with b_l on every curled preset, straight
    stays well below F_T and the curliest preset's full stroke reads above it (measured 0.01 and 10.09 N)."""
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.scene import PAIN_THRESHOLD

    t = fig_3_7_v3
    for name in list(PRESETS)[1:]:
        assert t[(name, 0.33)] < t[(name, 0.67)] < t[(name, 1.0)], name
    full = [t[(name, 1.0)] for name in PRESETS]
    assert full[0] < 0.5 and full[-1] > PAIN_THRESHOLD, full


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="under v3 the full-stroke force does not grow with curliness: straight 0.01, wavy 5.47, loose_curl 5.30, "
    "curly 11.40, tight_curl 9.28, coily 10.09 N (docs/detangling.md, *Figs 3.6(ii)–3.9 under v3*)",
)
def test_fig_3_7_order_under_v3(fig_3_7_v3) -> None:
    """Fig. 3.7 under v3: at b_l = 1 the mean max force grows with curliness, straight < … < coily."""
    from hairbrush_env.hair import PRESETS

    t = fig_3_7_v3
    full = np.array([t[(name, 1.0)] for name in PRESETS])
    assert np.all(np.diff(full) > 0), full


@pytest.mark.slow
def test_fig_3_7_under_v4_reduced() -> None:
    """Figs 3.6(ii) and 3.7 under ``HairBrush-v4``, reduced (seed 0, no abort): curly's stroke reads more the longer
    it is (measured 3.58 < 5.52 < 7.83 N at b_l 0.33 / 0.67 / 1), and at b_l = 1 wavy < loose_curl < curly (4.24 <
    6.46 < 7.83 N; under v3 wavy read about what loose_curl read and curly's force jumped only near b_l = 1)."""
    t = _mean_force(
        stroke_study.measure_strokes(
            ["curly"], brush_lengths=[0.33, 0.67, 1.0], seeds=[0], progress=False, physics="v4"
        )
        + stroke_study.measure_strokes(
            ["wavy", "loose_curl"], brush_lengths=[1.0], seeds=[0], progress=False, physics="v4"
        )
    )
    assert t[("curly", 0.33)] < t[("curly", 0.67)] < t[("curly", 1.0)]
    assert t[("wavy", 1.0)] < t[("loose_curl", 1.0)] < t[("curly", 1.0)]


@pytest.mark.slow
def test_fig_3_7_under_v7_reduced() -> None:
    """Figs 3.6(ii) and 3.7 under ``HairBrush-v7`` (smaller curls on tight_curl and coily), reduced (seed 0, no
    abort): at b_l = 1 curly < tight_curl < coily (measured 11.82 < 14.10 < 18.87 N; under v6, with all three curls
    at R = 12 mm, 11.82, 11.69 and 11.45 N), and coily's stroke from b_l 0.33 reads less than its full stroke
    (9.79 against 18.87 N)."""
    t = _mean_force(
        stroke_study.measure_strokes(
            ["curly", "tight_curl"], brush_lengths=[1.0], seeds=[0], progress=False, physics="v7"
        )
        + stroke_study.measure_strokes(
            ["coily"], brush_lengths=[0.33, 1.0], seeds=[0], progress=False, physics="v7"
        )
    )
    assert t[("curly", 1.0)] < t[("tight_curl", 1.0)] < t[("coily", 1.0)], t
    assert t[("coily", 0.33)] < t[("coily", 1.0)]


@pytest.mark.slow
def test_fig_3_7_under_v7() -> None:
    """Figs 3.6(ii) and 3.7 under v7, mean max force over seeds 0–2, no abort (``hairbrush strokes --physics v7
    --wigs all --brush-lengths 0.33,0.67,1 --seeds 3``): at b_l = 1 the force grows with curliness (measured 0.01 <
    3.82 < 9.59 < 11.77 < 13.67 < 18.87 N), straight stays well below F_T and the curliest full stroke reads above
    it; the shorter strokes read less than the full one on every curled preset, and coily's grows with b_l (9.84 <
    13.61 < 18.87 N). Curly and tight_curl read about as much at b_l 0.33 as at 0.67 (4.35 / 3.42 and 4.96 / 4.83 N;
    docs/detangling.md, *Not reproduced yet*)."""
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.scene import PAIN_THRESHOLD

    t = _fig_3_7_grid("v7")
    full = np.array([t[(name, 1.0)] for name in PRESETS])
    assert np.all(np.diff(full) > 0), full
    assert full[0] < 0.5 and full[-1] > PAIN_THRESHOLD, full
    for name in list(PRESETS)[1:]:
        assert max(t[(name, 0.33)], t[(name, 0.67)]) < t[(name, 1.0)], name
    assert t[("coily", 0.33)] < t[("coily", 0.67)] < t[("coily", 1.0)]


@pytest.mark.slow  # the default suite checks v10's Fig. 3.6(ii) instead (test_fig_3_6_ii_under_v10_reduced)
def test_fig_3_7_under_v8_reduced() -> None:
    """Fig. 3.6(ii) under ``HairBrush-v8`` (tines of the hair's friction 0.15, below every curl's lead-angle tangent),
    reduced (tight_curl, seed 0, no abort): the stroke reads more the longer it is (measured 4.21 < 7.45 < 11.83 N at
    b_l 0.33 / 0.67 / 1; under v7, its curls locked on the tines, 5.1 / 3.2 / 14.1 N) and the full stroke above F_T."""
    from hairbrush_env.scene import PAIN_THRESHOLD

    t = _mean_force(
        stroke_study.measure_strokes(
            ["tight_curl"], brush_lengths=[0.33, 0.67, 1.0], seeds=[0], progress=False, physics="v8"
        )
    )
    assert t[("tight_curl", 0.33)] < t[("tight_curl", 0.67)] < t[("tight_curl", 1.0)], t
    assert t[("tight_curl", 1.0)] > PAIN_THRESHOLD, t


def _assert_fig_3_7_order(t: dict, *, curly_short_below: float) -> None:
    """Figs 3.6(ii)/3.7 as v8, v9 and v10 meet them (v10 also meets curly's order, asserted by its own test): at
    b_l = 1 the force grows with curliness, straight well below F_T and the curliest above it; every curled preset's
    force grows with b_l but curly's, whose short strokes both stay below ``curly_short_below`` of its full stroke."""
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.scene import PAIN_THRESHOLD

    full = np.array([t[(name, 1.0)] for name in PRESETS])
    assert np.all(np.diff(full) > 0), full
    assert full[0] < 0.5 and full[-1] > PAIN_THRESHOLD, full
    for name in ("wavy", "loose_curl", "tight_curl", "coily"):
        assert t[(name, 0.33)] < t[(name, 0.67)] < t[(name, 1.0)], name
    assert max(t[("curly", 0.33)], t[("curly", 0.67)]) < curly_short_below * t[("curly", 1.0)]


@pytest.mark.slow
def test_fig_3_7_under_v8() -> None:
    """Figs 3.6(ii) and 3.7 under v8, mean max force over seeds 0–2, no abort (``hairbrush strokes --physics v8
    --wigs all --brush-lengths 0.33,0.67,1 --seeds 3``): at b_l = 1 the force grows with curliness (measured 0.01 <
    3.52 < 5.81 < 9.74 < 11.93 < 14.28 N), straight stays well below F_T and the curliest full stroke reads above it;
    every curled preset's force grows with b_l except curly's, whose b_l 0.33 reads a little more than its 0.67
    (3.41 against 3.02 N; docs/detangling.md, *HairBrush-v8*)."""
    _assert_fig_3_7_order(_fig_3_7_grid("v8"), curly_short_below=0.4)


@pytest.mark.slow
def test_fig_3_8_under_v8() -> None:
    """Fig. 3.8 under v8 (``hairbrush strokes --physics v8 --wigs curly,coily --brush-lengths 0.67,1 --speeds
    0.05,0.2 --seeds 3``): 0.05 → 0.2 m/s moves the mean max force by ≤ 25 % on coily at b_l 0.67 and 1 (measured
    +8 % and +8 %; v6: +72 % and +27 %) and on curly at b_l 0.67 (+19 %). Curly's full stroke moves by +52 % (7.9 →
    12.1 N; docs/detangling.md, *HairBrush-v8*), not asserted here."""
    table = _fig_3_8_table("v8")
    for wig, b_l in (("coily", 0.67), ("coily", 1.0), ("curly", 0.67)):
        slow, fast = table[(wig, b_l, 0.05)], table[(wig, b_l, 0.2)]
        assert abs(fast - slow) <= 0.25 * slow, (wig, b_l, slow, fast)


def test_fig_3_8_under_v9_reduced() -> None:
    """Fig. 3.8 under ``HairBrush-v9`` reduced to curly's full stroke, seed 0, no abort: 0.05 → 0.2 m/s moves the
    maximum by ≤ 25 % (measured 8.18 → 9.40 N, +15 %; under v8 7.92 → 13.19 N, +67 %). v9's drag leaves a curl that
    turns round a tine alone (``drag_normal_only``) and its tines spring back (docs/detangling.md, *HairBrush-v9*)."""
    rows = stroke_study.measure_strokes(
        ["curly"], brush_lengths=[1.0], speeds=[0.05, 0.2], seeds=[0], progress=False, physics="v9"
    )
    assert not any(r["diverged"] for r in rows)
    force = {r["speed"]: r["max_force"] for r in rows}
    assert abs(force[0.2] - force[0.05]) <= 0.25 * force[0.05], force


@pytest.mark.slow
def test_fig_3_8_under_v9() -> None:
    """Fig. 3.8 under v9 (``hairbrush strokes --physics v9 --wigs curly,coily --brush-lengths 0.67,1 --speeds
    0.05,0.2 --seeds 3``): 0.05 → 0.2 m/s moves the mean max force by ≤ 25 % on both wigs at both lengths (measured
    curly +24.6 % at b_l 0.67, at the bound's edge, and +15 % at 1, coily +6 % and +6 %; v8: +19, +52, +8, +8 %)."""
    table = _fig_3_8_table("v9")
    for wig in ("curly", "coily"):
        for b_l in (0.67, 1.0):
            slow, fast = table[(wig, b_l, 0.05)], table[(wig, b_l, 0.2)]
            assert abs(fast - slow) <= 0.25 * slow, (wig, b_l, slow, fast)


@pytest.mark.slow
def test_fig_3_7_under_v9() -> None:
    """Figs 3.6(ii) and 3.7 under v9 (``hairbrush strokes --physics v9 --wigs all --brush-lengths 0.33,0.67,1
    --seeds 3``), as under v8: at b_l = 1 the force grows with curliness (measured 0.01 < 3.71 < 5.06 < 9.50 < 11.84
    < 14.19 N), straight stays well below F_T and the curliest full stroke reads above it; every curled preset's force
    grows with b_l but curly's, whose b_l 0.33 reads more than its 0.67 (3.85 against 3.05 N: both maxima are the
    strands' ends released from the tines far below their rest, docs/detangling.md, *HairBrush-v9*)."""
    _assert_fig_3_7_order(_fig_3_7_grid("v9"), curly_short_below=0.45)


def test_fig_3_6_ii_under_v10_reduced() -> None:
    """Fig. 3.6(ii) under ``HairBrush-v10`` reduced to curly, seed 0, no abort: read as Algorithm 1 reads, while the
    brush is above the bottom of the hair, the stroke reads more the longer it is (measured 0.58 < 2.24 < 9.94 N at
    b_l 0.33 / 0.67 / 1). Under v9, which read the whole pull, the short strokes read the strands they had hooked and
    dragged below their rest free ends: 3.86 N at b_l 0.33, more than its 0.67 (docs/detangling.md, *HairBrush-v10*).
    """
    rows = stroke_study.measure_strokes(
        ["curly"], brush_lengths=[0.33, 0.67, 1.0], seeds=[0], progress=False, physics="v10"
    )
    assert not any(r["diverged"] for r in rows)
    read = {r["brush_length"]: r["max_force"] for r in rows}
    pull = {r["brush_length"]: r["pull_max_force"] for r in rows}
    assert read[0.33] < read[0.67] < read[1.0], read
    assert read[0.33] < 0.5 * pull[0.33] and read[1.0] == pytest.approx(pull[1.0]), (read, pull)


@pytest.mark.slow
def test_fig_3_7_under_v10() -> None:
    """Figs 3.6(ii) and 3.7 under v10 (``hairbrush strokes --physics v10 --wigs all --brush-lengths 0.33,0.67,1
    --seeds 3``), read as Algorithm 1 reads: at b_l = 1 the force grows with curliness (measured 0.01 < 3.71 < 5.06 <
    9.50 < 11.84 < 14.19 N), straight stays well below F_T and the curliest full stroke reads above it, and every
    curled preset's force grows with b_l, curly's too (0.61 < 2.41 < 9.50 N; under v9, reading the whole pull, 3.85 >
    3.05 N at b_l 0.33 / 0.67)."""
    t = _fig_3_7_grid("v10")
    _assert_fig_3_7_order(t, curly_short_below=0.3)
    assert t[("curly", 0.33)] < t[("curly", 0.67)] < t[("curly", 1.0)], t
