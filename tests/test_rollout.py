"""`hairbrush rollout` end to end and the rollout runner."""

from __future__ import annotations

import json
import os

os.environ.setdefault("MUJOCO_GL", "egl")

import gymnasium as gym
import pytest

import hairbrush_env  # noqa: F401
from hairbrush_env.cli import main
from hairbrush_env.hair import get_wig
from hairbrush_env.policies import available_policies, make_policy
from hairbrush_env.rollout import run_episode


def test_policies_registered_by_entry_point():
    assert {"full", "human", "naive", "random", "shortest", "sigmoid"} <= set(available_policies())
    with pytest.raises(ValueError, match="unknown policy 'nope'"):
        make_policy("nope", None)


SMALL_CURLY = get_wig("curly").replace(name="test_tiny_curly", n_strands=4, n_triples=0, length=0.16)


def _full_episode():
    env = gym.make("HairBrush-v0", wig=SMALL_CURLY, max_episode_steps=4)
    log = run_episode(env, make_policy("full", env), episode=0, seed=0, policy_name="full")
    env.close()
    return log


def test_run_episode_full_policy_runs_to_an_end():
    log = _full_episode()
    assert (log.terminated or log.truncated) and not log.diverged
    assert 1 <= len(log.steps) <= 4
    assert all(s.brush_length == pytest.approx(1.0) for s in log.steps)
    assert all(len(s.forces) == len(s.times) >= 1 for s in log.steps)
    assert log.sim_time > 0 and log.total_reward == pytest.approx(sum(s.reward for s in log.steps))


def test_episode_log_keeps_what_the_strokes_read_and_the_pulls_maxima():
    """Under ``HairBrush-v10`` a stroke reads only its first ``samples_read`` samples: the log's ``max_force`` is
    their largest, ``pull_max_force`` the whole pull's."""
    env = gym.make("HairBrush-v10", wig=SMALL_CURLY, max_episode_steps=2)
    log = run_episode(env, make_policy("naive", env), episode=0, seed=0, policy_name="naive")
    env.close()
    assert log.steps and not log.diverged
    for s in log.steps:
        assert s.max_force <= s.pull_max_force == pytest.approx(max(s.forces))
    assert any(s.max_force < s.pull_max_force for s in log.steps)
    summary = log.summary()
    assert summary["max_force"] == pytest.approx(max(s.max_force for s in log.steps))
    assert summary["pull_max_force"] == pytest.approx(max(s.pull_max_force for s in log.steps))


def test_rollout_applies_the_abort_each_policy_declares():
    """Naive and full strokes pull through, the closed loop stops at F_T, a policy that declares nothing gets the
    env's own abort; the episode log says which abort ran."""
    env = gym.make("HairBrush-v0", wig=SMALL_CURLY, max_episode_steps=1, abort_force=7.0)
    declared = {}
    for name in ("full", "naive", "human", "sigmoid", "random"):
        policy = make_policy(name, env, **({"curliness_hint": 0.5} if name == "sigmoid" else {}))
        declared[name] = run_episode(env, policy, episode=0, seed=0, policy_name=name).abort_force
    env.close()
    assert declared == {"full": None, "naive": None, "human": None, "sigmoid": 10.0, "random": 7.0}


def test_shortest_policy_never_finishes():
    """The stalling reference: every stroke at the lowest b_l, so eq. 3.4 (b_l = 1) never ends the episode."""
    env = gym.make("HairBrush-v0", wig=SMALL_CURLY, max_episode_steps=3)
    log = run_episode(env, make_policy("shortest", env), episode=0, seed=0, policy_name="shortest")
    env.close()
    assert log.truncated and not log.terminated and len(log.steps) == 3
    assert all(s.brush_length == pytest.approx(env.unwrapped.min_brush_length) for s in log.steps)


def test_rollout_cli_writes_everything(tmp_path):
    out = {k: tmp_path / f"out.{k}" for k in ("rrd", "webm", "json", "png")}
    code = main(
        [
            "rollout", "--wig", "straight", "--policy", "full", "--episodes", "1", "--seed", "3", "--quiet",
            "--max-steps", "2", "--wig-seed", "1",
            "--rerun", str(out["rrd"]), "--video", str(out["webm"]), "--json", str(out["json"]),
            "--plot", str(out["png"]),
        ]
    )  # fmt: skip
    assert code == 0
    data = json.loads(out["json"].read_text())
    (ep,) = data["episodes"]
    assert ep["policy"] == "full" and ep["wig"] == "straight" and ep["strokes"] >= 1
    assert ep["wig_seed"] == 1  # --wig-seed, not the state seed 3 draws (3)
    first = ep["steps"][0]
    assert len(first["forces"]) >= 10  # a full stroke sampled at 10 Hz
    assert len(first["times"]) == len(first["forces"])
    assert first["times"][1] - first["times"][0] == pytest.approx(0.1)
    for path in out.values():
        assert path.stat().st_size > 1000, path
    import cv2

    video = cv2.VideoCapture(str(out["webm"]))  # VP8 in WebM: a format browsers play
    codec = int(video.get(cv2.CAP_PROP_FOURCC)).to_bytes(4, "little").decode()
    n_frames, (ok, frame) = int(video.get(cv2.CAP_PROP_FRAME_COUNT)), video.read()
    video.release()
    assert codec.lower() in ("vp80", "vp08") and ok and frame.std() > 1.0, (codec, n_frames)
    with pytest.raises(SystemExit) as exc:
        main(["rollout", "--policy", "nope", "--quiet"])
    assert exc.value.code == 2
