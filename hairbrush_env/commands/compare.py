"""Policy × wig comparison grids: ``hairbrush compare``."""

from __future__ import annotations

import argparse


def _cmd_compare(args: argparse.Namespace) -> int:
    from ..compare import run_grid, summary_markdown

    if args.wigs == "all":
        from ..hair import PRESETS

        wigs = list(PRESETS)
    else:
        wigs = [w.strip() for w in args.wigs.split(",") if w.strip()]
    policies = [p.strip() for p in args.policies.split(",") if p.strip()]
    try:
        rows = run_grid(
            wigs, policies, episodes=args.episodes, seed=args.seed, out=args.out, progress=not args.quiet
        )
    except ValueError as exc:
        raise SystemExit(f"hairbrush compare: {exc}") from exc
    print(summary_markdown(rows))
    print(f"wrote {args.out}/results.csv, summary.md, max_force_vs_curliness.png, time_vs_curliness.png")
    return 0


def _add_compare(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "compare", help="run a policy x wig grid on HairBrush-v0 (CSV, Markdown summary, plots)"
    )
    p.add_argument("--wigs", default="all", help="comma-separated preset names, or 'all' (default)")
    p.add_argument(
        "--policies", default="sigmoid,naive,full", help="comma-separated policy names or sb3:PATH"
    )
    p.add_argument("--episodes", type=int, default=3, help="episodes per (wig, policy)")
    p.add_argument("--seed", type=int, default=0, help="episode k uses seed S + k for every policy")
    p.add_argument("--out", default="runs/compare", help="output directory (resumes an interrupted grid)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_compare)


def register(sub: argparse._SubParsersAction) -> None:
    _add_compare(sub)
