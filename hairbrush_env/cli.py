"""``hairbrush`` — one command-line tool with subcommands.

Each subcommand group lives in a ``_add_<group>`` function that registers its parser; the handlers import their
heavy dependencies lazily so ``hairbrush --help`` is instant.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__


def _load_curve(path: str):
    import numpy as np

    p = Path(path)
    if not p.exists():
        raise SystemExit(f"hairbrush: curve file not found: {path}")
    if p.suffix == ".npy":
        return np.load(p)
    return np.loadtxt(p, delimiter="," if p.suffix == ".csv" else None, ndmin=2)


def _cmd_topology_demo(args: argparse.Namespace) -> int:
    from .io import write_json
    from .topology.demo import plot_demo, run_demo
    from .viz import record_curves

    out = Path(args.out)
    res = run_demo(args.frames, seed=args.seed)
    plot_demo(res, out / "topology_demo.png")
    record_curves(out / "topology_demo.rrd", res.frames, times=res.x, scalars={"metrics/Lk": res.lk})
    summary = {
        "x": res.x,
        "lk": res.lk,
        "link_current": res.current,
        "census_per_metre": {k: {str(n): v for n, v in c.items()} for k, c in res.census.items()},
    }
    write_json(out / "topology_demo.json", summary)
    print(f"Lk at x=0: {res.lk[0]:.4f}, at x=1: {res.lk[-1]:.4f}")
    print(f"wrote {out / 'topology_demo.png'}, {out / 'topology_demo.rrd'}, {out / 'topology_demo.json'}")
    return 0


def _cmd_topology_lk(args: argparse.Namespace) -> int:
    from .topology import linking_number, writhe

    a, b = _load_curve(args.curve_a), _load_curve(args.curve_b)
    try:
        lk = linking_number(a, b, closed=not args.open)
        wa, wb = writhe(a, closed=not args.open), writhe(b, closed=not args.open)
    except ValueError as exc:
        raise SystemExit(f"hairbrush topology lk: {exc}") from exc
    print(f"Lk = {lk:.6f}\nWr(a) = {wa:.6f}\nWr(b) = {wb:.6f}")
    return 0


def _add_topology(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("topology", help="curve topology: linking number, writhe, link density, census")
    tsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")
    demo = tsub.add_parser(
        "demo", help="kinematic combing demo: writes a PNG figure, a rerun recording and JSON"
    )
    demo.add_argument("--out", default="runs/demo", help="output directory (default: runs/demo)")
    demo.add_argument("--frames", type=int, default=21, help="number of tine positions (default: 21)")
    demo.add_argument("--seed", type=int, default=0, help="seed of the random bundle for the census")
    demo.set_defaults(func=_cmd_topology_demo)
    lk = tsub.add_parser(
        "lk", help="linking number and writhes of two curves from .npy/.csv/.txt (N x 3) files"
    )
    lk.add_argument("curve_a")
    lk.add_argument("curve_b")
    lk.add_argument("--open", action="store_true", help="treat curves as open (real-valued Gauss integral)")
    lk.set_defaults(func=_cmd_topology_lk)


def _cmd_rollout(args: argparse.Namespace) -> int:
    import gymnasium as gym
    from tqdm import tqdm

    from .io import write_json
    from .policies import make_policy
    from .rollout import run_episode
    from .viz import EpisodeRecorder, VideoWriter, plot_rollout

    if args.episodes < 1:
        raise SystemExit(f"hairbrush rollout: --episodes must be >= 1, got {args.episodes}")
    try:
        env = gym.make(args.env, wig=args.wig, obs_mode=args.obs_mode, render_mode="rgb_array")
        policy = make_policy(args.policy, env)
    except ValueError as exc:
        raise SystemExit(f"hairbrush rollout: {exc}") from exc
    sim = env.unwrapped.sim
    recorder = EpisodeRecorder(args.rerun) if args.rerun else None
    video = VideoWriter(args.video) if args.video else None
    offset = 0.0

    def observe(sim_, t: float, force: float) -> None:
        # called by the simulation at every load-cell sample (10 Hz) inside strokes
        if recorder is not None:
            recorder.frame(t, sim_.strand_vertices(), sim_.strand_groups, sim_.brush_position(world=True))
            recorder.force(t, force)
        if video is not None:
            video.add(sim_.render(width=args.video_width, height=args.video_height))

    if recorder is not None or video is not None:
        sim.add_observer(observe)
    logs = []
    bar = tqdm(total=args.episodes, desc=f"{args.policy} on {args.wig}", unit="episode", disable=args.quiet)
    try:
        for ep in range(args.episodes):
            if recorder is not None:
                recorder.new_episode(ep, offset)

            def on_step(log, step, info) -> None:
                if recorder is not None:
                    t_end = info["sim_time"]
                    recorder.stroke(t_end, step.index, step.max_force, step.entanglement)
                    recorder.image(t_end, env.render())
                bar.set_postfix(
                    stroke=step.index + 1, f_max=f"{step.max_force:.1f}N", E=f"{step.entanglement:.2f}"
                )

            log = run_episode(
                env, policy, episode=ep, seed=args.seed + ep, policy_name=args.policy, on_step=on_step
            )
            offset += log.sim_time + 1.0
            logs.append(log)
            bar.update(1)
    finally:
        bar.close()
        env.close()
        if recorder is not None:
            recorder.close()
        if video is not None:
            video.close()
    episodes = [log.to_dict() for log in logs]
    for ep in episodes:
        print(
            f"episode {ep['episode']}: {ep['strokes']} strokes, max force {ep['max_force']:.2f} N, "
            f"pain violations {ep['pain_violations']}, entanglement {ep['entanglement_initial']:.2f} -> "
            f"{ep['final_entanglement']:.2f}, time {ep['time']:.1f} s{' (DIVERGED)' if ep['diverged'] else ''}"
        )
    if args.json:
        write_json(args.json, {"env": args.env, "wig": args.wig, "policy": args.policy, "episodes": episodes})
    if args.plot:
        plot_rollout(episodes, args.plot, force_threshold=env.unwrapped.force_threshold)
    for label, path in (
        ("recording", args.rerun),
        ("video", args.video),
        ("json", args.json),
        ("plot", args.plot),
    ):
        if path:
            print(f"wrote {label}: {path}")
    return 0


def _add_rollout(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "rollout", help="headless rollout of a policy on a brushing env (recording, video, plot)"
    )
    p.add_argument("--env", default="HairBrush-v0", choices=["HairBrush-v0", "HairBrushContinuous-v0"])
    p.add_argument("--wig", default="curly", help="wig preset name (see hairbrush_env.hair.PRESETS)")
    p.add_argument("--policy", default="full", help="registered policy name (e.g. full, random) or sb3:PATH")
    p.add_argument("--episodes", type=int, default=1)
    p.add_argument("--seed", type=int, default=0, help="episode k uses seed S + k")
    p.add_argument("--obs-mode", default="state+image", choices=["state", "image", "state+image"])
    p.add_argument("--rerun", metavar="OUT.rrd", help="write a rerun recording")
    p.add_argument("--video", metavar="OUT.mp4", help="write the webcam video (10 fps)")
    p.add_argument("--video-width", type=int, default=320)
    p.add_argument("--video-height", type=int, default=240)
    p.add_argument("--json", metavar="OUT.json", help="write per-episode metrics and per-stroke traces")
    p.add_argument("--plot", metavar="OUT.png", help="plot force vs time and max force per stroke")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_rollout)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hairbrush",
        description="Robotic hair brushing in MuJoCo and the physics/topology toolkit behind it.",
    )
    parser.add_argument("--version", action="version", version=f"hairbrush_env {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    _add_topology(sub)
    _add_rollout(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    # Headless rendering default for CLI runs; the library itself never forces a GL backend.
    os.environ.setdefault("MUJOCO_GL", "egl")
    args = build_parser().parse_args(argv)
    return int(args.func(args) or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
