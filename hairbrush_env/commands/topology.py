"""Curve topology commands: ``hairbrush topology demo|lk``."""

from __future__ import annotations

import argparse
from pathlib import Path


def _load_curve(path: str):
    import numpy as np

    p = Path(path)
    if not p.exists():
        raise SystemExit(f"hairbrush: curve file not found: {path}")
    if p.suffix == ".npy":
        return np.load(p)
    return np.loadtxt(p, delimiter="," if p.suffix == ".csv" else None, ndmin=2)


def _cmd_topology_demo(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..topology.demo import plot_demo, run_demo
    from ..viz import record_curves

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
    from ..topology import linking_number, writhe

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
        "lk", help="linking number and writhes of two curves from ..npy/.csv/.txt (N x 3) files"
    )
    lk.add_argument("curve_a")
    lk.add_argument("curve_b")
    lk.add_argument("--open", action="store_true", help="treat curves as open (real-valued Gauss integral)")
    lk.set_defaults(func=_cmd_topology_lk)


def register(sub: argparse._SubParsersAction) -> None:
    _add_topology(sub)
