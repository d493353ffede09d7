"""CT segmentation of rod piles (thesis §4.6): ``hairbrush rodpile segment|tomogram``.

``segment`` turns a grey-level stack (``.npy`` indexed x, y, z, or a multi-page ``.tif`` stack z, y, x) into one
straight rod per segment, written as a packing (``.npz`` + ``.csv``) that ``hairbrush rodpile fields`` reads.
``tomogram`` renders a packing into a synthetic stack (to validate the pipeline against ground truth).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from .checks import input_file, non_negative, number, output_file, positive, seed


def _cmd_rodpile_segment(args: argparse.Namespace) -> int:
    from ..io import write_json
    from ..studies.ct import load_tomogram, match_rods, segment_rods
    from ..studies.rod_pile import load_packing

    out = Path(args.out)
    if out.suffix != ".npz":
        raise SystemExit(f"hairbrush rodpile segment: --out must end in .npz, got {out}")
    try:
        tom = load_tomogram(args.volume, voxel_size=args.voxel_size, origin=args.origin, axes=args.axes)
        cd = args.container_diameter
        if cd is None:
            cd = float(tom.meta.get("container_diameter", float("nan")))
        seg = segment_rods(
            tom, diameter=args.diameter, container_diameter=cd, denoise_sigma=args.denoise_sigma, core=args.core,
            watershed_cut=args.watershed_cut, h=args.h, merge_gap=args.merge_gap, merge_angle=args.merge_angle,
            merge_cc_angle=args.merge_cc_angle, min_length=args.min_length, extend=args.extend,
            progress=not args.quiet,
        )  # fmt: skip
        truth = load_packing(args.truth) if args.truth else None
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile segment: {exc}") from exc
    seg.meta["source"] = str(args.volume)
    seg.save(out)
    seg.to_csv(out.with_suffix(".csv"))
    summary = {"volume": str(args.volume), "shape": list(tom.volume.shape), **seg.meta["ct"]}
    ct = seg.meta["ct"]
    print(
        f"{args.volume}: {tom.volume.shape} voxels of {tom.voxel_size * 1e3:.4g} mm (d = {ct['diameter_voxels']:.3g} "
        f"voxels) → {seg.n_rods} rods (skeleton pieces {ct['pieces']}, merged groups {ct['merged_groups']}, "
        f"debris dropped {ct['debris_dropped']})"
    )
    if truth is not None:
        m = match_rods(truth, seg, tol=args.tol)
        summary["validation"] = {
            "truth": str(args.truth), "n_truth": m.n_truth, "n_segmented": m.n_segmented,
            "recovered": int(m.recovered.sum()), "recovery": m.recovery, "tol_d": args.tol,
            "median_angle_error_deg": m.median_angle_error,
        }  # fmt: skip
        print(
            f"vs {args.truth}: recovered {m.recovered.sum()}/{m.n_truth} = {m.recovery:.1%} (both ends within "
            f"{args.tol:g} d), median axis-angle error {m.median_angle_error:.2f}°"
        )
    write_json(out.with_name(out.stem + "_summary.json"), summary)
    print(f"wrote {out}, {out.with_suffix('.csv')}, {out.with_name(out.stem + '_summary.json')}")
    return 0


def _cmd_rodpile_tomogram(args: argparse.Namespace) -> int:
    from ..studies.ct import synthetic_tomogram
    from ..studies.rod_pile import load_packing

    out = Path(args.out)
    try:
        p = load_packing(args.pile)
        vs = None if args.voxels_per_d is None else p.diameter / args.voxels_per_d
        tom = synthetic_tomogram(p, vs, noise=args.noise, blur=args.blur, seed=args.seed)
        tom.save(out)
    except ValueError as exc:
        raise SystemExit(f"hairbrush rodpile tomogram: {exc}") from exc
    print(
        f"wrote {out} ({tom.volume.shape} voxels of {tom.voxel_size * 1e3:.4g} mm, "
        f"{tom.volume.nbytes / 2**20:.0f} MiB) and {out.with_suffix('.json')} (voxel size, origin); "
        f"segment with --diameter {p.diameter!r}"
    )
    return 0


def add_segment_parser(rsub: argparse._SubParsersAction) -> None:
    """Add ``segment`` and ``tomogram`` to the ``hairbrush rodpile`` action sub-parsers."""
    s = rsub.add_parser(
        "segment", help="CT stack → rod centerlines (thesis §4.6); output feeds `rodpile fields`"
    )
    s.add_argument("volume", type=input_file, help=".npy (x, y, z) or .tif stack (z, y, x); a <stem>.json "
                   "sidecar supplies the voxel size and origin")  # fmt: skip
    s.add_argument("--diameter", type=positive, required=True, help="rod diameter d [m]")
    s.add_argument(
        "--voxel-size", type=positive, default=None, help="voxel edge [m] (default: from the sidecar)"
    )
    s.add_argument("--origin", type=float, nargs=3, default=None, metavar=("X", "Y", "Z"),
                   help="world corner of voxel (0,0,0) [m]; voxel (i,j,k) is centred at origin + (ijk+½)·voxel "
                   "(default: sidecar, else 0)")  # fmt: skip
    s.add_argument("--axes", choices=("xyz", "zyx"), default=None,
                   help="axis order of the array (default: sidecar, else xyz for .npy, zyx for .tif)")  # fmt: skip
    s.add_argument("--container-diameter", type=positive, default=None,
                   help="container diameter [m] for the field mask (cylinder axis x = y = 0, floor z = 0)")  # fmt: skip
    s.add_argument("--denoise-sigma", type=non_negative, default=0.8, help="Gaussian σ [voxels]")
    s.add_argument(
        "--core",
        type=number(0.0, exclusive=True, maximum=1.0),
        default=0.88,
        help="ridge level, fraction of the local max",
    )
    s.add_argument("--watershed-cut", action="store_true",
                   help="also cut along the first watershed (H-maxima markers of the EDT)")  # fmt: skip
    s.add_argument("--h", type=positive, default=0.1, help="H-maxima height [d] for --watershed-cut")
    s.add_argument("--merge-gap", type=non_negative, default=2.0, help="repair: max end-point distance [d]")
    s.add_argument(
        "--merge-angle", type=number(0.0, maximum=90.0), default=8.0, help="repair: max axis angle [deg]"
    )
    s.add_argument("--merge-cc-angle", type=number(0.0, maximum=90.0), default=4.0,
                   help="repair: max centre-to-centre vs axis angle [deg]")  # fmt: skip
    s.add_argument("--min-length", type=non_negative, default=3.0, help="drop rods shorter than this [d]")
    s.add_argument("--extend", type=non_negative, default=3.0, help="max end extension along the axis [d]")
    s.add_argument(
        "--truth",
        type=input_file,
        default=None,
        help="ground-truth packing: report recovery and angle errors",
    )
    s.add_argument("--tol", type=positive, default=1.0, help="recovered if both ends within tol·d")
    s.add_argument(
        "--out",
        type=output_file(".npz"),
        default="runs/rodpile/segments.npz",
        help="output packing (.npz; also .csv, json)",
    )
    s.add_argument("--quiet", action="store_true", help="no progress bars")
    s.set_defaults(func=_cmd_rodpile_segment)

    t = rsub.add_parser(
        "tomogram", help="render a packing into a synthetic CT stack (validation of `segment`)"
    )
    t.add_argument("pile", type=input_file, help="packing (.npz from generate, or CSV)")
    t.add_argument("--voxels-per-d", type=positive, default=None, help="voxels across a rod (default: 5)")
    t.add_argument("--noise", type=non_negative, default=0.15, help="noise σ / rod-air contrast")
    t.add_argument("--blur", type=non_negative, default=0.5, help="PSF σ [voxels]")
    t.add_argument("--seed", type=seed, default=0, help="seed of the noise")
    t.add_argument(
        "--out",
        type=output_file(".npy", ".tif", ".tiff"),
        default="runs/rodpile/volume.npy",
        help=".npy or .tif (+ .json sidecar)",
    )
    t.set_defaults(func=_cmd_rodpile_tomogram)
