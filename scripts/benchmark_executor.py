"""Wall time of one stroke grid on each executor, side by side in one run: local processes vs Ray, 1 vs 2 workers.

    python scripts/benchmark_executor.py [--wig curly] [--brush-lengths 0.2,0.35,0.5,0.65] [--seed 0]

Every executor runs the same grid (``hairbrush strokes``: one stroke per b_l from the pre-brushed wig of one seed,
``hairbrush_env.stroke_study.measure_strokes``) into a fresh directory; the table gives wall time, the speed-up
over local × 1, the summed CPU seconds of the cells (``cells.csv``) and whether ``strokes.csv`` is the same file,
byte for byte, as local × 1's. Ray's wall time includes starting a local Ray instance.
"""

from __future__ import annotations

import argparse
import csv
import os
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

from hairbrush_env.executor import ExecutorConfig, ray_available
from hairbrush_env.stroke_study import measure_strokes


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--wig", default="curly")
    p.add_argument("--brush-lengths", default="0.2,0.35,0.5,0.65")
    p.add_argument("--seed", type=int, default=0)
    a = p.parse_args()
    lengths = [float(x) for x in a.brush_lengths.split(",")]
    executors = [ExecutorConfig(1), ExecutorConfig(2)]
    if ray_available():
        executors += [ExecutorConfig(1, ray="auto"), ExecutorConfig(2, ray="auto")]
    rows, reference, base = [], None, None
    with tempfile.TemporaryDirectory() as tmp:
        for i, ex in enumerate(executors):
            out = Path(tmp) / str(i)
            t0 = time.perf_counter()
            measure_strokes(
                [a.wig], brush_lengths=lengths, seeds=[a.seed], out=out, executor=ex, progress=False
            )
            wall = time.perf_counter() - t0
            with open(out / "cells.csv", newline="") as fh:
                cpu = sum(float(r["cpu_seconds"]) for r in csv.DictReader(fh))
            data = (out / "strokes.csv").read_bytes()
            reference = data if reference is None else reference
            base = wall if base is None else base
            rows.append(
                [
                    ex.label,
                    f"{wall:.1f}",
                    f"{base / wall:.2f}",
                    f"{cpu:.1f}",
                    "yes" if data == reference else "NO",
                ]
            )
    print(
        f"\n{a.wig}, {len(lengths)} strokes (b_l {a.brush_lengths}, seed {a.seed}), {os.cpu_count()} CPUs\n"
    )
    header = ["executor", "wall s", "× local ×1", "cell CPU s", "same strokes.csv"]
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---:" if i else "---" for i in range(len(header))) + "|")
    for r in rows:
        print("| " + " | ".join(r) + " |")


if __name__ == "__main__":
    main()
