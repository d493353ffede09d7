"""Rod-pile study (chapter 4): ``hairbrush rodpile generate|sweep|compress|tension|fields|plot``."""

from __future__ import annotations

import argparse
from pathlib import Path


def _rodpile_summary(p) -> dict:
    import numpy as np

    from ..studies.rod_pile import (
        bulk_rods,
        contact_numbers,
        orientations,
        packing_fraction,
        philipse_contact_number,
        pile_height,
    )

    phi = packing_fraction(p)
    alpha = p.aspect_ratio
    c = contact_numbers(p)
    bulk = bulk_rods(p)
    theta, _ = orientations(p)
    cb = float(c[bulk].mean()) if bulk.any() else float("nan")
    return {
        "n_rods": p.n_rods, "alpha": alpha, "diameter": p.diameter, "height": pile_height(p), "phi_f": phi,
        "phi_alpha": phi * alpha, "mean_contacts_all": float(c.mean()), "mean_contacts_bulk": cb,
        "n_bulk_rods": int(bulk.sum()), "philipse_contacts": philipse_contact_number(phi, alpha),
        "mean_cos_theta": float(np.cos(theta).mean()), "lost_rods": p.meta.get("lost_rods", 0),
    }  # fmt: skip


def _print_summary(tag: str, s: dict) -> None:
    print(
        f"{tag}: n={s['n_rods']} α={s['alpha']:.1f} H={s['height'] * 1e3:.1f} mm φ_f={s['phi_f']:.4f} "
        f"φα={s['phi_alpha']:.2f} ⟨c⟩bulk={s['mean_contacts_bulk']:.2f} (all {s['mean_contacts_all']:.2f}) "
        f"Philipse={s['philipse_contacts']:.2f} ⟨cosθ⟩={s['mean_cos_theta']:.3f}"
    )


def _cmd_rodpile_generate(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import generate_packing, plot_structure

    out = Path(args.out)
    d = args.length / args.alpha
    try:
        p = generate_packing(
            args.n_rods, args.length, d, container_diameter=args.container * args.length, seed=args.seed,
            jostle=not args.no_jostle, batch_size=args.batch, friction=args.friction, progress=not args.quiet,
        )  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile generate: {exc}") from exc
    p.save(out)
    p.to_csv(out.with_suffix(".csv"))
    s = _rodpile_summary(p)
    write_json(out.with_name(out.stem + "_summary.json"), s)
    plot_structure({"generated": p}, out.with_name(out.stem + "_structure.png"))
    _print_summary(str(out), s)
    return 0


def _cmd_rodpile_sweep(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import generate_packing, load_packing, plot_phi_alpha

    out = Path(args.out)
    rows = []
    for alpha, n in zip(args.alphas, args.n_rods, strict=True):
        path = out / f"pile_alpha{alpha:g}_seed{args.seed}.npz"
        if path.exists():  # resume: piles already generated are reused
            p = load_packing(path)
        else:
            p = generate_packing(n, args.length, args.length / alpha, container_diameter=args.container * args.length,
                                 seed=args.seed, friction=args.friction, batch_size=args.batch,
                                 progress=not args.quiet)  # fmt: skip
            p.save(path)
        s = _rodpile_summary(p)
        _print_summary(f"α={alpha:g}", s)
        rows.append(s)
        write_json(out / "sweep.json", rows)
    plot_phi_alpha([r["alpha"] for r in rows], [r["phi_f"] for r in rows], out / "phi_alpha.png",
                   contacts=[r["mean_contacts_bulk"] for r in rows])  # fmt: skip
    print(f"wrote {out / 'sweep.json'}, {out / 'phi_alpha.png'}")
    return 0


def _cmd_rodpile_compress(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import compress, load_packing, plot_compression, plot_structure

    out = Path(args.out)
    try:
        p = load_packing(args.pile)
        res = compress(p, args.strain_max, args.cycles, args.rate, snapshot_strains=[args.strain_max],
                       progress=not args.quiet)  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile compress: {exc}") from exc
    res.save(out / "compression.npz")
    squeezed = res.snapshots[args.strain_max]
    squeezed.save(out / "compressed.npz")
    res.final.save(out / "after.npz")
    summary = {
        "h0": res.h0, "weight": res.weight, "max_load": res.max_load, "dissipated_J": res.dissipated,
        "before": _rodpile_summary(p), "after_unloading": _rodpile_summary(res.final),
    }  # fmt: skip
    write_json(out / "compression.json", summary)
    plot_compression(res, out / "compression.png")
    plot_structure({"ε = 0": p, f"ε = {args.strain_max:g}": squeezed}, out / "structure.png")
    print("max load per cycle [N]: " + ", ".join(f"{x:.4g}" for x in res.max_load))
    print("dissipated per cycle [mJ]: " + ", ".join(f"{x * 1e3:.4g}" for x in res.dissipated))
    print(f"wrote {out}/compression.npz, compressed.npz, after.npz, compression.json, compression.png")
    return 0


def _cmd_rodpile_tension(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.rod_pile import load_packing, plot_tension, tension

    out = Path(args.out)
    try:
        res = tension(load_packing(args.pile), glue_depth=args.glue_depth, strain_max=args.strain_max,
                      progress=not args.quiet)  # fmt: skip
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile tension: {exc}") from exc
    write_json(out / "tension.json", {k: getattr(res, k) for k in res.__dataclass_fields__})
    plot_tension(res, out / "tension.png")
    print(f"disentanglement energy {res.energy * 1e3:.4g} mJ, separation at {res.separation * 1e3:.3g} mm "
          f"(glued: {res.n_glued_top} top, {res.n_glued_bottom} bottom)")  # fmt: skip
    return 0


def _cmd_rodpile_fields(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from ..io import write_json
    from ..studies.rod_fields import correlations, local_fields, plot_fields
    from ..studies.rod_pile import load_packing

    out = Path(args.out)
    fields, summary = {}, {}
    for path in tqdm(args.piles, desc="fields", unit="pile", disable=args.quiet):
        try:
            p = load_packing(path)
            spacing = None if args.spacing is None else args.spacing * p.diameter
            f = local_fields(p, args.ls * p.diameter, spacing=spacing, shape=args.shape)
        except ValueError as exc:
            raise SystemExit(f"hairbrush rodpile fields: {exc}") from exc
        label = f"ε = {f.meta.get('strain', 0.0):.3g}"
        while label in fields:
            label += "'"
        fields[label] = f
        f.save(out / f"fields_{Path(path).stem}.npz")
        corr = correlations(f)
        summary[str(path)] = {
            "label": label, "cells": int(f.mask.sum()), "means": f.means(),
            "correlation_length_over_ls": {k: v[2] / f.cell_size for k, v in corr.items()},
        }  # fmt: skip
        means = ", ".join(f"{k}={v:.4g}" for k, v in f.means().items())
        xi = ", ".join(f"{k}:{v[2] / f.cell_size:.2f}" for k, v in corr.items())
        print(f"{path} [{label}, {f.mask.sum()} cells]: {means}\n  ξ/l_s: {xi}")
    write_json(out / "fields.json", summary)
    pngs = plot_fields(fields, out / "fields")
    print("wrote " + ", ".join(str(x) for x in [out / "fields.json", *pngs]))
    return 0


def _cmd_rodpile_plot(args: argparse.Namespace) -> int:
    from ..studies.rod_fields import Fields, plot_fields

    out = Path(args.dir)
    files = sorted(out.glob("fields_*.npz"))
    if not files:
        raise SystemExit(f"hairbrush rodpile plot: no fields_*.npz in {out}")
    fields = {}
    for f in files:
        fl = Fields.load(f)
        fields[f"{f.stem[7:]} (ε = {fl.meta.get('strain', 0.0):.3g})"] = fl
    print("wrote " + ", ".join(str(x) for x in plot_fields(fields, out / "fields")))
    return 0


def _add_rodpile(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "rodpile", help="random packings of rigid rods: generate, compress, pull, fields (thesis ch. 4)"
    )
    rsub = p.add_subparsers(dest="action", required=True, metavar="ACTION")

    def common(q, pile_arg=True):
        if pile_arg:
            q.add_argument("pile", help="packing file (.npz from generate, or CSV of endpoints / rod,x,y,z)")
        q.add_argument("--quiet", action="store_true", help="no progress bars")

    g = rsub.add_parser("generate", help="drop, jostle and settle rods in a cylinder (§4.5.1)")
    g.add_argument("--n-rods", type=int, default=150)
    g.add_argument("--alpha", type=float, default=20.0, help="aspect ratio L/d (default 20)")
    g.add_argument("--length", type=float, default=0.05, help="rod length [m] (default 0.05)")
    g.add_argument(
        "--container", type=float, default=3.0, help="container diameter in rod lengths (default 3)"
    )
    g.add_argument("--friction", type=float, default=0.4)
    g.add_argument("--batch", type=int, default=10, help="rods dropped together (default 10)")
    g.add_argument("--seed", type=int, default=0)
    g.add_argument("--no-jostle", action="store_true")
    g.add_argument("--out", default="runs/rodpile/pile.npz")
    common(g, pile_arg=False)
    g.set_defaults(func=_cmd_rodpile_generate)

    s = rsub.add_parser("sweep", help="φ_f and ⟨c⟩ vs aspect ratio (Fig. 4.5); resumable")
    s.add_argument("--alphas", type=float, nargs="+", default=[38.0, 76.0, 100.0])
    s.add_argument("--n-rods", type=int, nargs="+", default=[400, 800, 1000], help="rods per α")
    s.add_argument("--length", type=float, default=0.05)
    s.add_argument("--container", type=float, default=3.0)
    s.add_argument("--friction", type=float, default=0.4)
    s.add_argument("--batch", type=int, default=20)
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--out", default="runs/rodpile/sweep")
    common(s, pile_arg=False)
    s.set_defaults(func=_cmd_rodpile_sweep)

    c = rsub.add_parser("compress", help="piston load–strain cycles (Figs 4.2, 4.6)")
    common(c)
    c.add_argument("--strain-max", type=float, default=0.15)
    c.add_argument("--cycles", type=int, default=3)
    c.add_argument("--rate", type=float, default=None, help="strain rate [1/s] (default: quasi-static)")
    c.add_argument("--out", default="runs/rodpile/compress")
    c.set_defaults(func=_cmd_rodpile_compress)

    t = rsub.add_parser("tension", help="glue top/bottom layers and pull apart (Fig. 5.3)")
    common(t)
    t.add_argument("--glue-depth", type=float, default=0.15, help="glued layer thickness / pile height")
    t.add_argument("--strain-max", type=float, default=1.0, help="plate lift / pile height")
    t.add_argument("--out", default="runs/rodpile/tension")
    t.set_defaults(func=_cmd_rodpile_tension)

    f = rsub.add_parser("fields", help="φ, S, e, n fields, histograms, maps, correlations (Figs 4.3, 4.4)")
    f.add_argument("piles", nargs="+", help="packings (e.g. pile.npz compressed.npz)")
    f.add_argument("--ls", type=float, default=10.0, help="cell size l_s in rod diameters (default 10)")
    f.add_argument("--spacing", type=float, default=None, help="grid spacing in diameters (default l_s)")
    f.add_argument("--shape", choices=("cube", "sphere"), default="cube")
    f.add_argument("--out", default="runs/rodpile/fields")
    f.add_argument("--quiet", action="store_true")
    f.set_defaults(func=_cmd_rodpile_fields)

    pl = rsub.add_parser("plot", help="redraw the field figures from fields_*.npz in a directory")
    pl.add_argument("dir")
    pl.set_defaults(func=_cmd_rodpile_plot)


def register(sub: argparse._SubParsersAction) -> None:
    _add_rodpile(sub)
