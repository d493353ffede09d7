"""A rod pile's structure summarized in numbers (thesis chapter 4; ``hairbrush rodpile summary``)."""

from __future__ import annotations

__all__ = ["pile_summary"]


def pile_summary(p) -> dict:
    """Structure of a packing ``p`` in numbers: φ_f and φ_f α (whole pile, away from the wall layer, per height slab,
    vs wall margin, in radial annuli), contact numbers (all, bulk) against Philipse's ⟨c⟩ = 2 φ α (isotropic,
    oriented, local φ), orientation order ⟨cos θ⟩, pile height and the generation's bookkeeping (thesis chapter 4,
    Fig. 4.5; what ``hairbrush rodpile summary`` prints and stores)."""
    import math

    import numpy as np

    from .packing import pile_height
    from .structure import (
        bulk_rods,
        contact_numbers,
        mean_abs_sin,
        orientations,
        packing_fraction,
        phi_seen,
        philipse_contact_number,
        radial_packing_fraction,
    )

    phi = packing_fraction(p)
    alpha = p.aspect_ratio
    length = float(np.mean(p.lengths))
    # φ away from the wall layer too (inner cylinder R − L/2), when the container is ≥ 2 L wide
    inner = p.container_diameter / 2 - length / 2
    wide = inner >= 0.5 * length * (1 - 1e-9)
    phi_in = packing_fraction(p, wall_margin=length / 2) if wide else math.nan
    c = contact_numbers(p)
    bulk = bulk_rods(p)
    theta, _ = orientations(p)
    cb = float(c[bulk].mean()) if bulk.any() else float("nan")
    msin = mean_abs_sin(p, bulk) if bulk.sum() >= 2 else math.nan
    phi_b = phi_seen(p, bulk) if bulk.any() else math.nan  # φ around the bulk rods (radial profile)
    # height profile: φ (inner cylinder if wide enough) and ⟨cos θ⟩ of rods centred in 5 slabs of H
    zc = p.endpoints.mean(axis=1)[:, 2] / pile_height(p)
    profile = []
    for lo in np.arange(5) / 5:
        sel = (zc >= lo) & (zc < lo + 0.2)
        ph = packing_fraction(p, slab=(lo, lo + 0.2), wall_margin=length / 2 if wide else 0.0)
        profile.append({"slab": [float(lo), float(lo + 0.2)], "phi_alpha": ph * alpha, "n_rods": int(sel.sum()),
                        "mean_cos_theta": float(np.cos(theta[sel]).mean()) if sel.any() else math.nan})  # fmt: skip
    radius = p.container_diameter / 2
    radial = {f"{m:g}": packing_fraction(p, wall_margin=m * length) * alpha
              for m in (0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8) if m * length < 0.9 * radius}  # fmt: skip
    _, annuli = radial_packing_fraction(p, 6)
    return {
        "n_rods": p.n_rods, "alpha": alpha, "diameter": p.diameter, "height": pile_height(p),
        "height_over_L": pile_height(p) / length, "phi_f": phi, "phi_alpha": phi * alpha,
        "phi_f_inner": phi_in, "phi_alpha_inner": phi_in * alpha,
        "mean_contacts_all": float(c.mean()), "mean_contacts_bulk": cb,
        "n_bulk_rods": int(bulk.sum()), "philipse_contacts": philipse_contact_number(phi, alpha),
        "contacts_bulk_over_philipse": cb / philipse_contact_number(phi, alpha),
        "contacts_bulk_over_philipse_inner": cb / philipse_contact_number(phi_in, alpha) if wide else math.nan,
        "mean_abs_sin_bulk": msin, "philipse_contacts_oriented": philipse_contact_number(phi, alpha, msin),
        "phi_seen_by_bulk_rods": phi_b, "philipse_contacts_local": philipse_contact_number(phi_b, alpha),
        "contacts_bulk_over_philipse_local": cb / philipse_contact_number(phi_b, alpha),
        "mean_cos_theta": float(np.cos(theta).mean()),
        "mean_cos_theta_bulk": float(np.cos(theta[bulk]).mean()) if bulk.any() else float("nan"),
        "lost_rods": p.meta.get("lost_rods", 0), "generation_s": p.meta.get("wall_time_s", math.nan),
        "profile": profile, "phi_alpha_vs_wall_margin_over_L": radial,
        "phi_alpha_annuli": (annuli * alpha).tolist(),
    }  # fmt: skip
