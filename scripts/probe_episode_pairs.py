"""Exploration probe: one policy episode, then which entwined pairs are still wound (docs/detangling.md).

    python scripts/probe_episode_pairs.py WIG POLICY SEED     # e.g. curly sigmoid 0

Runs the episode as ``hairbrush compare`` does (webcam images for the vision policies, the policy's own abort) and
prints its strokes and every entwined pair's signed link at the end, next to the link it was built with.
"""

import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import gymnasium as gym

import hairbrush_env  # noqa: F401  (registers the envs)
from hairbrush_env.policies import make_policy
from hairbrush_env.rollout import run_episode

wig, name, seed = sys.argv[1], sys.argv[2], int(sys.argv[3])
env = gym.make("HairBrush-v0", wig=wig, obs_mode="state+image", width=640, height=480)
log = run_episode(env, make_policy(name, env), episode=0, seed=seed, policy_name=name)
sim = env.unwrapped.sim
print(f"{name} on {wig}, seed {seed}: {len(log.steps)} strokes")
print("  b_l   ", " ".join(f"{s.brush_length or 0:.2f}" for s in log.steps))
print("  F_max ", " ".join(f"{s.max_force:.1f}" for s in log.steps))
print(f"  Σ|Lk| {log.entanglement_initial:.2f} -> {log.steps[-1].entanglement:.2f}")
print("  pair Lk now:   ", " ".join(f"{v:+.2f}" for v in sim.pair_links()))
print("  pair Lk built: ", " ".join(f"{v:+.2f}" for v in sim.layout.pair_link))
print("  still entwined:", sim.entanglement_meter.still_entwined(sim.data), "of", len(sim.layout.pairs))
