"""Brushing rollouts: ``hairbrush rollout``."""

from __future__ import annotations

import argparse

from . import add_webcam_args
from .checks import count, output_file, policy_choices, policy_name, seed, wig_choices, wig_field, wig_name


def _cmd_rollout(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from ..envs import make_version
    from ..io import write_json
    from ..physics import get_physics
    from ..policies import make_policy
    from ..rollout import run_episode
    from ..viz import EpisodeRecorder, VideoWriter, plot_rollout

    version = args.env.rsplit("-", 1)[1]  # HairBrush-v10 and HairBrushContinuous-v10 brush under physics v10
    try:
        env = make_version(
            args.env,
            wig=args.wig,
            obs_mode=args.obs_mode,
            render_mode="rgb_array",
            width=args.width,
            height=args.height,
            **({"max_episode_steps": args.max_steps} if args.max_steps is not None else {}),
            # one pre-brushed state for every episode: how a compare cell is reproduced with its stroke traces
            **({"wig_seeds": (args.wig_seed,)} if args.wig_seed is not None else {}),
            # the version's own wig fields stay: wig_fields given to an env replace them
            **({"wig_fields": {**get_physics(version).wig_fields, **dict(args.set)}} if args.set else {}),
        )
        policy = make_policy(args.policy, env)
    except ValueError as exc:
        raise SystemExit(f"hairbrush rollout: {exc}") from exc
    sim = env.unwrapped.sim
    recorder = EpisodeRecorder(args.rerun) if args.rerun else None
    video = VideoWriter(args.video) if args.video else None
    offset = 0.0

    # colour strands by their entwined group
    group_of = {i: g for g, members in enumerate(sim.layout.groups) for i in members}
    groups = [group_of.get(i, 0) for i in range(len(sim.layout.names))]

    def observe(sim_, sample) -> None:
        # called by the simulation at every load-cell sample (10 Hz), with the episode's simulated time
        if recorder is not None:
            recorder.frame(
                sample.time, sim_.hair_curves(), groups, sim_.bristle_segments(), sim_.bristle_radius
            )
            recorder.force(sample.time, sample.brushing_force())
        if video is not None:
            video.add(sim_.render())

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
            f"{ep['entanglement_final']:.2f}, time {ep['sim_time']:.1f} s{' (DIVERGED)' if ep['diverged'] else ''}"
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
    from ..envs import ENV_IDS
    from ..physics import physics_help

    def env_id(text: str) -> str:
        if text in ENV_IDS:
            return text
        # a compact list: the ids are the two envs at every physics version
        versions = sorted({int(k.rsplit("-v", 1)[1]) for k in ENV_IDS})
        raise argparse.ArgumentTypeError(
            f"unknown env id {text!r}; valid: HairBrush-vN and HairBrushContinuous-vN for N = "
            f"{versions[0]}…{versions[-1]}"
        )

    p.add_argument(
        "--env",
        default="HairBrush-v0",
        type=env_id,
        metavar="ENV",
        help=f"env id (HairBrush-vN or HairBrushContinuous-vN); its version's physics: {physics_help()}",
    )
    p.add_argument("--wig", type=wig_name, default="curly", help=f"wig: {', '.join(wig_choices())}")
    p.add_argument(
        "--policy",
        type=policy_name,
        default="full",
        help=f"policy: {', '.join(policy_choices())}, or sb3:DIR",
    )
    p.add_argument("--episodes", type=count, default=1, help="episodes to run")
    p.add_argument("--seed", type=seed, default=0, help="episode k uses seed S + k")
    p.add_argument(
        "--wig-seed",
        type=seed,
        default=None,
        help="start every episode from pre-brushed state W (the wig_seed column of compare's results.csv), "
        "e.g. to get a compare row's stroke traces (default: the seed draws one of the wig's states)",
    )
    p.add_argument(
        "--set",
        action="append",
        type=wig_field,
        default=[],
        metavar="FIELD=VALUE",
        help="set a WigConfig field on the wig, on top of the env version's (a JSON value; repeatable), e.g. "
        "root_run=1 to spread the curl starts over a whole pitch",
    )
    p.add_argument(
        "--max-steps",
        type=count,
        default=None,
        help="cap on env steps per episode (default: the registered limit)",
    )
    p.add_argument(
        "--obs-mode", default="state+image", choices=["state", "image", "state+image"], help="observations"
    )
    p.add_argument("--rerun", metavar="OUT.rrd", type=output_file(".rrd"), help="write a rerun recording")
    p.add_argument(
        "--video",
        metavar="OUT.webm",
        type=output_file(".webm", ".mp4"),
        help="write the webcam video (10 fps): .webm (VP8, plays in browsers) or .mp4 (mp4v, video players only)",
    )
    add_webcam_args(p)
    p.add_argument(
        "--json",
        metavar="OUT.json",
        type=output_file(".json"),
        help="write per-episode metrics and stroke traces",
    )
    p.add_argument(
        "--plot",
        metavar="OUT.png",
        type=output_file(".png", ".pdf", ".svg"),
        help="plot force and entanglement",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_rollout)


def register(sub: argparse._SubParsersAction) -> None:
    _add_rollout(sub)
