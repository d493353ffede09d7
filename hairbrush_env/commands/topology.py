"""Curve topology commands: ``hairbrush topology demo|lk``."""

from __future__ import annotations

import argparse
from pathlib import Path

from .checks import UsageError, count, input_file, output_dir, seed

#: Ends farther apart than this many mean edge lengths make a curve "open" for the warning of ``topology lk``.
OPEN_GAP_EDGES = 3.0


def _load_curve(path: str, flag: str):
    """An ``(N >= 2, 3)`` float array from a .npy, .csv or whitespace-separated file; UsageError otherwise."""
    import numpy as np

    p = Path(path)
    try:
        if p.suffix == ".npy":
            arr = np.load(p)
        else:
            arr = np.loadtxt(p, delimiter="," if p.suffix == ".csv" else None, ndmin=2)
    except (ValueError, OSError) as exc:
        raise UsageError(flag, f"cannot read {path!r} as an N x 3 array of numbers: {exc}") from None
    arr = np.asarray(arr, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 3 or len(arr) < 2 or not np.all(np.isfinite(arr)):
        raise UsageError(flag, f"{path!r} must hold N >= 2 rows of 3 finite numbers, got shape {arr.shape}")
    return arr


def _looks_open(curve) -> bool:
    import numpy as np

    edges = np.linalg.norm(np.diff(curve, axis=0), axis=1)
    return float(np.linalg.norm(curve[-1] - curve[0])) > OPEN_GAP_EDGES * float(edges.mean())


def _cmd_topology_demo(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.topology_demo import plot_demo, run_demo
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
    import sys

    from ..topology import linking_number, writhe

    a, b = _load_curve(args.curve_a, "curve_a"), _load_curve(args.curve_b, "curve_b")
    if not args.open:
        for name, curve in (("curve_a", a), ("curve_b", b)):
            if _looks_open(curve):
                print(
                    f"hairbrush topology lk: warning: {name} looks open (its ends are more than {OPEN_GAP_EDGES:g} "
                    "mean edges apart) but is closed by a straight segment; pass --open for the open-curve "
                    "Gauss integral",
                    file=sys.stderr,
                )
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
    demo.add_argument("--out", type=output_dir, default="runs/demo", help="output directory")
    demo.add_argument("--frames", type=count, default=21, help="number of tine positions")
    demo.add_argument("--seed", type=seed, default=0, help="seed of the random bundle for the census")
    demo.set_defaults(func=_cmd_topology_demo)
    lk = tsub.add_parser(
        "lk", help="linking number and writhes of two curves from ..npy/.csv/.txt (N x 3) files"
    )
    lk.add_argument("curve_a", type=input_file, help="first curve: .npy, .csv or .txt with N x 3 coordinates")
    lk.add_argument("curve_b", type=input_file, help="second curve, same formats")
    lk.add_argument("--open", action="store_true", help="treat curves as open (real-valued Gauss integral)")
    lk.set_defaults(func=_cmd_topology_lk)


def register(sub: argparse._SubParsersAction) -> None:
    _add_topology(sub)
