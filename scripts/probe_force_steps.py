"""Exploration probe: how long a force peak lasts at the physics step, against what the 10 Hz load cell reports.

    python scripts/probe_force_steps.py WIG SEED STROKES      # e.g. curly 0 5 (the default's jam at stroke 5)

Repeated full strokes (b_l = 1, no abort). For each stroke: the largest load-cell sample (10 Hz, sampled at an
instant, as ``sensors.LoadCell`` does), the largest brushing force at any 1 ms physics step, how many milliseconds
the per-step force stayed ≥ 10 N, and the largest mean over any 0.1 s window (what a converter that integrates over
its sampling period, such as a sigma-delta load-cell amplifier at 10 samples/s, would report at most).
"""

import os
import sys

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
import numpy as np

from hairbrush_env.scene import BrushingSim, SceneConfig

wig, seed, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
sim = BrushingSim(SceneConfig(wig=wig))
sim.reset(seed)
trace: list[tuple[float, float]] = []


def observe(s: BrushingSim) -> None:
    trace.append((float(s.data.time), s.load_cell.measure(s.data).brushing_force()))


sim.add_step_observer(observe)
for k in range(1, n + 1):
    trace.clear()
    res = sim.stroke(1.0, abort_force=None)
    t, f = np.array(trace).T
    dt = np.diff(t)
    window = max(1, round(0.1 / float(np.median(dt))))
    mean = np.convolve(f, np.ones(window) / window, mode="valid")
    above = float(dt[f[:-1] >= 10.0].sum()) * 1e3
    i = int(np.argmax(f))
    print(
        f"stroke {k}: load cell {res.max_force:.1f} N; per step max {f.max():.1f} N at t {t[i]:.3f} s; "
        f"≥ 10 N for {above:.0f} ms; largest 0.1 s mean {mean.max():.1f} N",
        flush=True,
    )
