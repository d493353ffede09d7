"""Recordings and figures (hairbrush_env.viz)."""

from __future__ import annotations

import numpy as np

from hairbrush_env.viz import EpisodeRecorder


def test_episode_recording_draws_the_tines_and_stores_frames_compressed(tmp_path) -> None:
    """A recording of 10 webcam frames with strands and a 23-tine comb: written atomically, and the images stored as
    JPEG, so the file is far smaller than the raw frames it holds (10 × 320 × 240 × 3 bytes)."""
    h, w = 240, 320
    yy, xx = np.mgrid[0:h, 0:w]
    strands = [
        np.column_stack([np.full(26, 0.01 * i), np.zeros(26), np.linspace(0.9, 0.6, 26)]) for i in range(4)
    ]
    tines = np.stack(
        [np.array([[-0.03, y, 0.8], [0.03, y, 0.8]]) for y in np.linspace(-0.22, 0.22, 23)]
    )  # (23, 2, 3) axis segments
    path = tmp_path / "episode.rrd"
    rec = EpisodeRecorder(path)
    rec.new_episode(0, 0.0)
    for k in range(10):
        img = np.stack([(xx + 7 * k) % 256, (yy + 3 * k) % 256, np.full((h, w), 90)], axis=-1).astype(
            np.uint8
        )
        rec.frame(0.1 * k, strands, [0, 0, 1, 1], tines, 1e-3)
        rec.force(0.1 * k, float(k))
        rec.image(0.1 * k, img)
    assert not path.exists()  # atomic: nothing at the final path before close
    rec.close()
    raw = 10 * h * w * 3
    assert 1_000 < path.stat().st_size < 0.25 * raw, path.stat().st_size


def test_rollout_plot_marks_a_stroke_aborted_at_its_first_sample(tmp_path, monkeypatch) -> None:
    """A one-sample stroke between the NaN breaks draws no line; the force panel must still show its force."""
    from hairbrush_env import viz

    step = {"times": [0.1, 0.2], "forces": [2.0, 3.0], "max_force": 3.0, "entanglement": 5.0}
    aborted = {"times": [1.1], "forces": [14.5], "max_force": 14.5, "entanglement": 5.0}
    episode = {"policy": "sigmoid", "wig": "coily", "episode": 0, "entanglement_initial": 6.0,
               "steps": [step, aborted]}  # fmt: skip
    marked: list[float] = []
    save = viz.save_figure

    def capture(fig, path):
        for line in fig.axes[0].get_lines():  # the load-cell panel
            if line.get_marker() == "o":
                marked.extend(np.asarray(line.get_ydata(), dtype=float).tolist())
        save(fig, path)

    monkeypatch.setattr(viz, "save_figure", capture)
    viz.plot_rollout([episode], tmp_path / "rollout.png")
    assert marked == [14.5]
    assert (tmp_path / "rollout.png").exists()
