"""The numbers of a pile summary agree with each other and with the pile (a geometric rod gas: no mechanics)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hairbrush_env.studies.rod_pile import packing_fraction, philipse_contact_number, random_rod_gas
from hairbrush_env.studies.rod_pile.summary import pile_summary


def test_summary_of_an_isotropic_gas():
    length, alpha = 0.05, 20.0
    gas = random_rod_gas(
        400, length, length / alpha, container_diameter=3 * length, height=2 * length, seed=0
    )
    s = pile_summary(gas)
    assert s["n_rods"] == 400 and s["alpha"] == pytest.approx(alpha)
    assert s["phi_f"] == pytest.approx(packing_fraction(gas)) and s["phi_alpha"] == pytest.approx(
        s["phi_f"] * alpha
    )
    assert s["philipse_contacts"] == pytest.approx(philipse_contact_number(s["phi_f"], alpha))
    assert sum(p["n_rods"] for p in s["profile"]) == 400  # the five height slabs hold every rod once
    assert abs(s["mean_cos_theta"] - 0.5) < 0.08  # isotropic: ⟨|cos θ|⟩ = 1/2
    assert len(s["phi_alpha_annuli"]) == 6 and all(np.isfinite(s["phi_alpha_annuli"]))
    assert not math.isnan(s["phi_f_inner"])  # a 3 L container is wide enough for the inner cylinder
