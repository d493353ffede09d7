"""Draw the learning curves of a training run (``scripts/train_rl.py`` does this at the end, too) and print
what the agent's strokes looked like in each quarter of training (the reward-hacking check).

    python scripts/plot_learning_curves.py runs/rl/sac_curly [--out PNG] [--window 5]
"""

from __future__ import annotations

import argparse

from controllers.learning_curves import plot_learning_curves, stroke_summary, stroke_summary_markdown


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run_dir")
    p.add_argument("--out", default=None, help="PNG path (default RUN_DIR/learning_curves.png)")
    p.add_argument("--window", type=int, default=5, help="running-mean window in episodes")
    a = p.parse_args()
    print(f"wrote {plot_learning_curves(a.run_dir, a.out, window=a.window)}")
    table = stroke_summary(a.run_dir)
    if table:  # stroke-level env: what the agent's strokes looked like over training (reward-hacking check)
        print(stroke_summary_markdown(table))


if __name__ == "__main__":
    main()
