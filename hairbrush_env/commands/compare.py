"""Policy × wig comparison grids and single-stroke force studies: ``hairbrush compare``, ``hairbrush strokes``."""

from __future__ import annotations

import argparse

from . import add_webcam_args


def _wig_names(text: str) -> list[str]:
    """Comma-separated wig names, ``all`` for every preset (straightest first), or ``held_out`` for RL's held-out
    wigs (``hair.HELD_OUT_WIGS``, brushed from the held-out pre-brushed states)."""
    from ..hair import HELD_OUT_WIGS, PRESETS

    if text == "all":
        return list(PRESETS)
    if text == "held_out":
        return list(HELD_OUT_WIGS)
    return [w.strip() for w in text.split(",") if w.strip()]


def _cmd_compare(args: argparse.Namespace) -> int:
    from ..compare import run_grid, summary_markdown

    wigs = _wig_names(args.wigs)
    policies = [p.strip() for p in args.policies.split(",") if p.strip()]
    try:
        rows = run_grid(
            wigs,
            policies,
            episodes=args.episodes,
            seed=args.seed,
            out=args.out,
            env_kwargs={"width": args.width, "height": args.height},
            workers=args.workers,
            progress=not args.quiet,
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
    p.add_argument(
        "--wigs",
        default="all",
        help="comma-separated wig names, 'all' presets (default) or 'held_out' (RL's test wigs)",
    )
    p.add_argument(
        "--policies", default="sigmoid,naive,full", help="comma-separated policy names or sb3:PATH"
    )
    p.add_argument("--episodes", type=int, default=3, help="episodes per (wig, policy)")
    p.add_argument("--seed", type=int, default=0, help="episode k uses seed S + k for every policy")
    p.add_argument("--out", default="runs/compare", help="output directory (resumes an interrupted grid)")
    p.add_argument("--workers", type=int, default=1, help="episodes run in this many processes")
    add_webcam_args(p)
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_compare)


def _floats(text: str) -> list[float]:
    try:
        return [float(v) for v in text.split(",") if v.strip()]
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"expected comma-separated numbers, got {text!r}") from exc


def _cmd_strokes(args: argparse.Namespace) -> int:
    from ..stroke_study import measure_strokes, summary_markdown

    wigs = _wig_names(args.wigs)
    try:
        rows = measure_strokes(
            wigs,
            brush_lengths=args.brush_lengths,
            speeds=args.speeds,
            seeds=range(args.seed, args.seed + args.seeds),
            out=args.out,
            progress=not args.quiet,
        )
    except ValueError as exc:
        raise SystemExit(f"hairbrush strokes: {exc}") from exc
    print(summary_markdown(rows))
    print(f"wrote {args.out}/strokes.csv, summary.md, force_vs_brush_length.png, force_vs_speed.png")
    return 0


def _add_strokes(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "strokes",
        help="max force of single strokes vs curliness, brush length and speed (thesis Figs 3.7, 3.8)",
    )
    p.add_argument("--wigs", default="straight,curly,coily", help="comma-separated preset names, or 'all'")
    p.add_argument(
        "--brush-lengths", type=_floats, default=[1.0], help="normalized start heights b_l, e.g. 0.33,0.67,1"
    )
    p.add_argument("--speeds", type=_floats, default=[0.1], help="pull speeds [m/s], e.g. 0.05,0.1,0.2")
    p.add_argument("--seeds", type=int, default=3, help="repetitions (pre-brushed wigs S, S+1, ...)")
    p.add_argument("--seed", type=int, default=0, help="first seed S")
    p.add_argument("--out", default="runs/strokes", help="output directory (resumes an interrupted run)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_strokes)


def _cmd_repeat(args: argparse.Namespace) -> int:
    from ..studies.repeated_strokes import run_repeated, summary_markdown

    wigs = _wig_names(args.wigs)
    for flag, value, ok in (
        ("--strokes", args.strokes, args.strokes >= 1),
        ("--seeds", args.seeds, args.seeds >= 1),
        ("--seed", args.seed, args.seed >= 0),
        ("--brush-length", args.brush_length, 0.0 < args.brush_length <= 1.0),
    ):
        if not ok:
            raise SystemExit(f"hairbrush repeat: {flag} {value!r} is out of range")
    try:
        rows = run_repeated(
            wigs,
            seeds=range(args.seed, args.seed + args.seeds),
            n_strokes=args.strokes,
            brush_length=args.brush_length,
            out=args.out,
            progress=not args.quiet,
        )
    except ValueError as exc:
        raise SystemExit(f"hairbrush repeat: {exc}") from exc
    print(summary_markdown(rows))
    print(f"wrote {args.out}/repeat.csv, summary.md, repeat.png")
    return 0


def _add_repeat(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "repeat",
        help="repeated full strokes: force and entanglement per stroke (thesis Fig. 3.6(i), eq. 3.4)",
        formatter_class=argparse.ArgumentDefaultsHelpFormatter,
    )
    p.add_argument("--wigs", default="curly,coily", help="comma-separated preset names, or 'all'")
    p.add_argument("--strokes", type=int, default=6, help="strokes per series")
    p.add_argument(
        "--brush-length", type=float, default=1.0, help="normalized start height b_l of every stroke"
    )
    p.add_argument("--seeds", type=int, default=3, help="series (pre-brushed wigs S, S+1, ...)")
    p.add_argument("--seed", type=int, default=0, help="first seed S")
    p.add_argument(
        "--out", default="runs/repeat", help="output directory (keeps the complete series of a rerun)"
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_repeat)


def register(sub: argparse._SubParsersAction) -> None:
    _add_compare(sub)
    _add_strokes(sub)
    _add_repeat(sub)
