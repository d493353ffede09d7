"""Fitting k: the sigmoid must lie below every (R_c, largest safe length) point."""

from __future__ import annotations

import math

import numpy as np
import pytest

from controllers.sigmoid import start_height
from controllers.sigmoid_fit import fit_k


def test_fit_k_lies_below_points_and_is_tight():
    rc = [0.1, 0.3, 0.6, 0.8, 0.95]
    safe = [1.0, 0.9, 0.3, 0.12, 0.05]
    k, lo, hi = fit_k(rc, safe)
    assert math.isfinite(k) and lo <= k <= hi
    for r, s in zip(rc, safe, strict=True):
        assert start_height(r, k=k) <= s + 1e-12
    # tight: the binding point sits on the curve
    assert min(s - start_height(r, k=k) for r, s in zip(rc, safe, strict=True)) == pytest.approx(
        0.0, abs=1e-9
    )


def test_fit_k_reports_conflict():
    # a straight wig that cannot take even 60 % strokes and a curly one that takes 90 %: no sigmoid fits
    k, lo, hi = fit_k([0.1, 0.9], [0.2, 0.9])
    assert np.isnan(k) and lo > hi
