"""Policy × wig comparison grids and single-stroke force studies: ``hairbrush compare``, ``hairbrush strokes``."""

from __future__ import annotations

import argparse

from . import add_executor_args, add_physics_arg, add_webcam_args, executor_from_args
from .checks import (
    count,
    number,
    number_list,
    output_dir,
    policy_choices,
    policy_names,
    positive,
    seed,
    wig_choices,
    wig_names,
)


def _cmd_compare(args: argparse.Namespace) -> int:
    from ..compare import run_grid, summary_markdown

    try:
        rows = run_grid(
            args.wigs,
            args.policies,
            episodes=args.episodes,
            seed=args.seed,
            out=args.out,
            env_kwargs={"width": args.width, "height": args.height},
            executor=executor_from_args(args),
            progress=not args.quiet,
            physics=args.physics,
        )
    except ValueError as exc:
        raise SystemExit(f"hairbrush compare: {exc}") from exc
    print(summary_markdown(rows))
    print(f"wrote {args.out}/results.csv, summary.md, max_force_vs_curliness.png, time_vs_curliness.png")
    return 0


def _add_compare(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "compare", help="run a policy x wig grid on any HairBrush-vN physics (CSV, Markdown summary, plots)"
    )
    p.add_argument(
        "--wigs",
        type=wig_names(),
        default="all",
        help=f"comma-separated wig names ({', '.join(wig_choices())}), 'all' presets or 'held_out' (RL's test wigs)",
    )
    p.add_argument(
        "--policies",
        type=policy_names,
        default="sigmoid,naive,full",
        help=f"comma-separated policy names ({', '.join(policy_choices())}) or sb3:DIR",
    )
    p.add_argument("--episodes", type=count, default=3, help="episodes per (wig, policy)")
    p.add_argument("--seed", type=seed, default=0, help="episode k uses seed S + k for every policy")
    p.add_argument(
        "--out",
        type=output_dir,
        default="runs/compare",
        help="output directory (resumes an interrupted grid)",
    )
    add_physics_arg(p)
    add_executor_args(p, workers=1, what="episodes")
    add_webcam_args(p)
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_compare)


def _cmd_strokes(args: argparse.Namespace) -> int:
    from ..stroke_study import measure_strokes, summary_markdown

    try:
        rows = measure_strokes(
            args.wigs,
            brush_lengths=args.brush_lengths,
            speeds=args.speeds,
            seeds=range(args.seed, args.seed + args.seeds),
            out=args.out,
            executor=executor_from_args(args),
            progress=not args.quiet,
            physics=args.physics,
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
    p.add_argument(
        "--wigs", type=wig_names(), default="straight,curly,coily", help="comma-separated wig names, or 'all'"
    )
    p.add_argument(
        "--brush-lengths",
        type=number_list(number(0.0, exclusive=True, maximum=1.0)),
        default="1",
        help="normalized start heights b_l in (0, 1], e.g. 0.33,0.67,1",
    )
    p.add_argument(
        "--speeds", type=number_list(positive), default="0.1", help="pull speeds [m/s], e.g. 0.05,0.1,0.2"
    )
    p.add_argument("--seeds", type=count, default=3, help="repetitions (pre-brushed wigs S, S+1, ...)")
    p.add_argument("--seed", type=seed, default=0, help="first seed S")
    p.add_argument(
        "--out", type=output_dir, default="runs/strokes", help="output directory (resumes an interrupted run)"
    )
    add_physics_arg(p)
    add_executor_args(p, workers=1, what="strokes")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_strokes)


def _cmd_repeat(args: argparse.Namespace) -> int:
    from ..studies.repeated_strokes import run_repeated, summary_markdown

    try:
        rows = run_repeated(
            args.wigs,
            seeds=range(args.seed, args.seed + args.seeds),
            n_strokes=args.strokes,
            brush_length=args.brush_length,
            out=args.out,
            progress=not args.quiet,
            physics=args.physics,
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
    )
    p.add_argument(
        "--wigs", type=wig_names(), default="curly,coily", help="comma-separated wig names, or 'all'"
    )
    p.add_argument("--strokes", type=count, default=6, help="strokes per series")
    p.add_argument(
        "--brush-length",
        type=number(0.0, exclusive=True, maximum=1.0),
        default=1.0,
        help="normalized start height b_l of every stroke, in (0, 1]",
    )
    p.add_argument("--seeds", type=count, default=3, help="series (pre-brushed wigs S, S+1, ...)")
    p.add_argument("--seed", type=seed, default=0, help="first seed S")
    p.add_argument(
        "--out",
        type=output_dir,
        default="runs/repeat",
        help="output directory (keeps the complete series of a rerun)",
    )
    add_physics_arg(p)
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_repeat)


def register(sub: argparse._SubParsersAction) -> None:
    _add_compare(sub)
    _add_strokes(sub)
    _add_repeat(sub)
