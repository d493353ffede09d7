"""Learning curves read the training Monitor logs in the order episodes ended, across workers."""

from __future__ import annotations

import json

import numpy as np
import pytest

from controllers.learning_curves import plot_learning_curves, training_episodes


def _monitor(path, t_start, rows):
    header = "r,l,t,entanglement,entanglement_initial"
    lines = ["#" + json.dumps({"t_start": t_start, "env_id": "HairBrush-v0"}), header]
    lines += [",".join(str(v) for v in row) for row in rows]
    path.write_text("\n".join(lines) + "\n")


def test_episodes_of_two_workers_are_merged_by_end_time(tmp_path):
    mon = tmp_path / "monitor"
    mon.mkdir()
    # worker 1 started 5 s after worker 0; its first episode (t = 3 s) ends at 8 s, between worker 0's two
    _monitor(mon / "0.monitor.csv", 100.0, [(-1.0, 30, 4.0, 9.0, 10.0), (2.0, 30, 20.0, 6.0, 10.0)])
    _monitor(mon / "1.monitor.csv", 105.0, [(0.5, 20, 3.0, 8.0, 10.0)])
    rows = training_episodes(tmp_path)
    assert [r["r"] for r in rows] == [-1.0, 0.5, 2.0]
    assert [r["timesteps"] for r in rows] == [30.0, 50.0, 80.0]
    assert rows[1]["t"] == pytest.approx(8.0)
    png = plot_learning_curves(tmp_path, window=2)
    assert png.exists() and png.stat().st_size > 1000


def test_missing_monitor_logs_name_the_directory(tmp_path):
    with pytest.raises(ValueError, match="monitor"):
        training_episodes(tmp_path)


def test_running_mean_is_causal():
    from controllers.learning_curves import _smooth

    y = np.array([0.0, 2.0, 4.0, 6.0])
    assert _smooth(y, 2).tolist() == [0.0, 1.0, 3.0, 5.0]


def test_stroke_summary_flags_a_collapse_to_the_shortest_stroke(tmp_path):
    """The hacking check: per quarter of training, the share of strokes at the lowest b_l and the finishes."""
    from controllers.learning_curves import stroke_summary, stroke_summary_markdown

    lines = ["timesteps,env,action_0,reward,done,brush_length,max_force,aborted,reward_finish"]
    for t in range(1, 41):
        b_l = 0.1 if t > 20 else 0.7  # drifts to the floor in the second half
        lines.append(f"{t},0,0.0,-0.1,False,{b_l},1.0,{t % 10 == 0},{5.0 if t == 5 else 0.0}")
    (tmp_path / "steps.csv").write_text("\n".join(lines) + "\n")
    table = stroke_summary(tmp_path, parts=4)
    assert [t["at_min"] for t in table] == [0.0, 0.0, 1.0, 1.0]
    assert [t["finishes"] for t in table] == [1.0, 0.0, 0.0, 0.0]
    assert [t["reached_F_T"] for t in table] == [0.1] * 4
    assert table[0]["steps"] == "1–10" and "| 1–10 | 0.70 | 0% |" in stroke_summary_markdown(table)
