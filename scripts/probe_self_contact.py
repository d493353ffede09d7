"""Exploration probe: do strands pass through themselves? (By default hair strands have no self-collision,
``WigConfig.self_collision``, and the pass-through monitor watches pairs of different strands only.)

    python scripts/probe_self_contact.py WIG SEED STROKES [WIG_FIELDS_JSON]     # e.g. curly 0 6
    python scripts/probe_self_contact.py curly 0 6 '{"self_collision": true}'   # with self-collision

Repeated full strokes (b_l = 1, no abort). After every physics step, the smallest distance between the centerlines
of any two non-adjacent segments of one strand, as a fraction of the wisp diameter 2 r (the sum of the two radii):
below 1 the strand's capsules overlap, near 0 a segment passes through another of the same strand. Prints per stroke
the smallest such distance, the number of steps and of distinct (strand, segment, segment) triples below 0.5, and
the maximum load-cell force.
"""

import json
import os
import sys
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env import hair
from hairbrush_env.scene import BrushingSim, SceneConfig

wig_name, seed, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
fields = json.loads(sys.argv[4]) if len(sys.argv) > 4 else {}
sim = BrushingSim(SceneConfig(wig=hair.PRESETS[wig_name].replace(**fields)))
sim.reset(seed)
diameter = 2.0 * sim.wig.strand_radius


def segment_distances(p0, p1, q0, q1):
    """Distances between segments p0–p1 and q0–q1 (arrays of shape (..., 3)), clamped closest points."""
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a = np.einsum("...i,...i", d1, d1)
    e = np.einsum("...i,...i", d2, d2)
    f = np.einsum("...i,...i", d2, r)
    c = np.einsum("...i,...i", d1, r)
    b = np.einsum("...i,...i", d1, d2)
    denom = a * e - b * b
    s = np.where(denom > 1e-18, np.clip((b * f - c * e) / np.maximum(denom, 1e-18), 0.0, 1.0), 0.0)
    t = (b * s + f) / e
    s = np.where(t < 0.0, np.clip(-c / a, 0.0, 1.0), np.where(t > 1.0, np.clip((b - c) / a, 0.0, 1.0), s))
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(p0 + d1 * s[..., None] - (q0 + d2 * t[..., None]), axis=-1)


n_seg = sim.hair_curve_array().shape[1] - 1
ii, jj = np.triu_indices(n_seg, k=2)
state = {"min": np.inf, "steps": 0, "triples": set()}


def observe(s: BrushingSim) -> None:
    c = s.hair_curve_array()  # (strands, points, 3)
    dist = segment_distances(c[:, ii], c[:, ii + 1], c[:, jj], c[:, jj + 1]) / diameter  # (strands, pairs)
    state["min"] = min(state["min"], float(dist.min()))
    close = np.argwhere(dist < 0.5)
    if len(close):
        state["steps"] += 1
        state["triples"].update((int(k), int(ii[p]), int(jj[p])) for k, p in close)


sim.add_step_observer(observe)
print(f"{wig_name} seed {seed} {fields}: {n_seg} segments a strand", flush=True)
for k in range(1, n + 1):
    state.update(min=np.inf, steps=0, triples=set())
    cpu = time.process_time()
    res = sim.stroke(1.0, abort_force=None)
    cpu = time.process_time() - cpu
    strands = sorted({t[0] for t in state["triples"]})
    print(
        f"stroke {k}: F_max {res.max_force:.1f} N; entanglement {sim.entanglement():.2f}; smallest self distance "
        f"{state['min']:.2f} (2r); steps below 0.5: {state['steps']}; segment pairs below 0.5: "
        f"{len(state['triples'])} on strands {strands}; {cpu:.0f} CPU s (with this probe's check)",
        flush=True,
    )
