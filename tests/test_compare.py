"""Comparison grid bookkeeping (:mod:`hairbrush_env.compare`): CSV round trip, resume, summary statistics."""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import numpy as np
import pytest

from hairbrush_env import compare
from hairbrush_env.executor import ExecutorConfig
from hairbrush_env.io import write_csv_rows


def _row(wig: str, policy: str, episode: int, max_force: float, curliness: float = 0.5) -> dict:
    return {
        "wig": wig,
        "R_over_P": curliness,
        "policy": policy,
        "abort_force": None if policy == "naive" else 10.0,
        "episode": episode,
        "seed": episode,
        "wig_seed": episode % 4,
        "max_force": max_force,
        "pull_max_force": max_force + 1.0,
        "sim_time": 10.0 + episode,
        "strokes": 3 + episode,
        "pain_violations": int(max_force >= 10.0),
        "entanglement_final": 1.5,
        "entanglement_initial": 4.0,
        "total_reward": -0.25,
        "diverged": False,
        "not_a_column": "dropped",
    }


def test_results_csv_round_trip(tmp_path) -> None:
    rows = [_row("curly", "naive", 0, 12.5), _row("curly", "sigmoid", 1, 8.0)]
    write_csv_rows(tmp_path / "results.csv", rows, compare.COLUMNS)
    back = compare.read_results(tmp_path / "results.csv")
    assert [set(r) for r in back] == [set(compare.COLUMNS)] * 2
    for r, b in zip(rows, back, strict=True):
        assert all(b[k] == r[k] for k in compare.COLUMNS)
        assert isinstance(b["episode"], int) and isinstance(b["max_force"], float) and b["diverged"] is False


def test_finished_cells_are_not_rerun(tmp_path) -> None:
    rows = [_row("curly", "naive", 0, 12.5)]
    write_csv_rows(tmp_path / "results.csv", rows, compare.COLUMNS)
    # every requested cell is already in results.csv, so no env is made and nothing is simulated
    out = compare.run_grid(["curly"], ["naive"], episodes=1, seed=0, out=tmp_path, progress=False)
    assert len(out) == 1 and out[0]["max_force"] == 12.5
    assert (tmp_path / "summary.md").read_text().count("| curly |") == 1
    assert (tmp_path / "max_force_vs_curliness.png").stat().st_size > 0


def test_summary_mean_and_std() -> None:
    rows = [_row("curly", "naive", e, f) for e, f in enumerate((12.0, 8.0, 10.0))]
    rows.append(_row("straight", "naive", 0, 1.0, curliness=0.0))
    table = compare.summarize(rows)
    assert [e["wig"] for e in table] == ["straight", "curly"]  # sorted by curliness
    curly = table[1]
    assert curly["n"] == 3
    assert curly["max_force"][0] == pytest.approx(10.0)
    assert curly["max_force"][1] == pytest.approx(np.std([12.0, 8.0, 10.0], ddof=1))
    assert curly["pain_violations"][0] == pytest.approx(2 / 3)
    assert curly["total_reward"] == (pytest.approx(-0.25), pytest.approx(0.0))
    assert curly["pull_max_force"][0] == pytest.approx(11.0)
    assert (
        "| curly | 0.50 | naive | 3 | -0.25 ± 0.00 | 10.00 ± 2.00 | 11.00 ± 2.00 |"
        in compare.summary_markdown(rows)
    )


def test_bad_episode_count(tmp_path) -> None:
    with pytest.raises(ValueError, match="episodes"):
        compare.run_grid(["curly"], ["naive"], episodes=0, seed=0, out=tmp_path, progress=False)
    with pytest.raises(ValueError, match="workers"):
        ExecutorConfig(workers=0)


@pytest.mark.slow
def test_naive_hurts_on_the_curliest_wig_sigmoid_does_not(tmp_path) -> None:
    """Thesis §3.6 (reduced to 4 strokes on the curliest preset): the naive thirds policy reaches the pain
    threshold F_T, the sigmoid closed loop (vision R_c → eq. 3.3 → Algorithm 1) stays below it."""
    from hairbrush_env.hair import PRESETS
    from hairbrush_env.scene import PAIN_THRESHOLD

    curliest = list(PRESETS)[-1]
    rows = compare.run_grid(
        [curliest],
        ["naive", "sigmoid"],
        episodes=1,
        seed=0,
        out=tmp_path,
        env_kwargs={"max_episode_steps": 4, "width": 640, "height": 480},
        executor=ExecutorConfig(workers=2),  # also exercises the process-parallel grid
        progress=False,
    )
    by_policy = {r["policy"]: r for r in rows}
    assert not any(r["diverged"] for r in rows)
    assert by_policy["naive"]["max_force"] >= PAIN_THRESHOLD and by_policy["naive"]["pain_violations"] >= 1
    assert by_policy["sigmoid"]["max_force"] < PAIN_THRESHOLD and by_policy["sigmoid"]["pain_violations"] == 0


@pytest.mark.slow
@pytest.mark.xfail(
    strict=True,
    reason="seed 0: naive 6 strokes / 22.15 s, sigmoid 4 strokes / 16.87 s. Straight full strokes read 0.3–3.3 N "
    "from one stroke to the next, against eq. 3.4's 0.4 N tolerance, so which policy meets the finish rule first is "
    "chance in a single episode; issue 21 asks for this over 3 episodes on wigs that detangle",
)
def test_naive_finishes_faster_than_sigmoid(tmp_path) -> None:
    """Thesis Fig. 3.11 (bottom), reduced to the straight wig: naive thirds finishes in less brushing time than the
    sigmoid closed loop, whose Algorithm 1 needs more strokes before eq. 3.4 says finished."""
    rows = compare.run_grid(
        ["straight"],
        ["naive", "sigmoid"],
        episodes=1,
        seed=0,
        out=tmp_path,
        env_kwargs={"width": 640, "height": 480},
        executor=ExecutorConfig(workers=2),
        progress=False,
    )
    by_policy = {r["policy"]: r for r in rows}
    assert not any(r["diverged"] for r in rows)
    assert by_policy["naive"]["sim_time"] < by_policy["sigmoid"]["sim_time"], by_policy


def test_a_grid_runs_on_the_env_of_its_physics_version_and_never_mixes_them(tmp_path, monkeypatch) -> None:
    """``physics="v1"`` runs every cell on HairBrush-v1 (recorded in physics.json); resuming that grid under v0
    is refused before anything runs."""
    made = []
    monkeypatch.setattr(
        compare, "run_cell", lambda *args: made.append(args[-1]) or _row("curly", "naive", 0, 3.0)
    )
    compare.run_grid(["curly"], ["naive"], episodes=1, seed=0, out=tmp_path, progress=False, physics="v1")
    assert made == ["HairBrush-v1"]
    with pytest.raises(ValueError, match="holds results under v1"):
        compare.run_grid(["curly"], ["naive"], episodes=2, seed=0, out=tmp_path, progress=False)
    assert made == ["HairBrush-v1"]


def test_unknown_names_fail_before_anything_is_simulated(tmp_path) -> None:
    with pytest.raises(ValueError, match="unknown policy 'bogus'"):
        compare.run_grid(["curly"], ["full", "bogus"], episodes=1, seed=0, out=tmp_path, progress=False)
    with pytest.raises(ValueError, match="valid names"):
        compare.run_grid(["curlyy"], ["full"], episodes=1, seed=0, out=tmp_path, progress=False)
    assert not (tmp_path / "results.csv").exists()


def test_episodes_of_a_cell_meet_distinct_pre_brushed_wigs(monkeypatch) -> None:
    """Episode k of every cell starts from the k-th pre-brushed state of its wig (cycling), the same for every
    policy; the held-out wigs from the held-out states."""
    import gymnasium

    import hairbrush_env.policies
    import hairbrush_env.rollout
    from hairbrush_env.hair import HELD_OUT_SEEDS, TRAIN_WIG_SEEDS

    seen = []

    class Log:
        def __init__(self, wig_seed):
            self.wig_seed = wig_seed

        def summary(self):
            return {"wig_seed": self.wig_seed}

    def fake_episode(env, policy, *, episode, seed, policy_name, wig_seed=None, on_step=None):
        seen.append((env, policy_name, episode, seed, wig_seed))
        return Log(wig_seed)

    monkeypatch.setattr(gymnasium, "make", lambda *a, **kw: ("env", kw["wig"], tuple(kw["wig_seeds"])))
    monkeypatch.setattr(hairbrush_env.policies, "make_policy", lambda name, env: name)
    monkeypatch.setattr(hairbrush_env.rollout, "run_episode", fake_episode)
    monkeypatch.setattr(compare, "_ENVS", {})
    for policy in ("naive", "sigmoid"):
        for episode in range(5):
            compare.run_cell("curly", policy, episode, 10, {})
    for episode in range(3):
        compare.run_cell("held_out_curly", "naive", episode, 10, {})
    curly = [s for s in seen if s[0][1] == "curly"]
    assert [s[4] for s in curly] == [TRAIN_WIG_SEEDS[e % len(TRAIN_WIG_SEEDS)] for e in range(5)] * 2
    assert [s[3] for s in curly[:5]] == [10, 11, 12, 13, 14]
    assert [s[4] for s in seen[10:]] == list(HELD_OUT_SEEDS)
    assert all(s[0][2] == HELD_OUT_SEEDS for s in seen[10:])


def test_results_written_before_v10_read_back_with_the_pull_maximum(tmp_path) -> None:
    """A ``results.csv`` without ``pull_max_force`` (written before v10 read part of a pull) reads back with it equal
    to ``max_force``: those versions read the whole pull."""
    rows = [_row("curly", "naive", 0, 12.5)]
    old_columns = [c for c in compare.COLUMNS if c != "pull_max_force"]
    write_csv_rows(tmp_path / "results.csv", rows, old_columns)
    (back,) = compare.read_results(tmp_path / "results.csv")
    assert back["pull_max_force"] == back["max_force"] == 12.5
