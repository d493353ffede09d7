"""Vision curliness R_c (eq. 3.5) on synthetic hair images with known geometry."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from scipy.stats import spearmanr

from controllers.vision import curliness, gradient_images, gradient_ratio, hair_roi


def draw_hair(curl_ratio: float, *, seed=0, colour=(60, 40, 20), background=(235, 235, 235), size=(240, 200)):
    """Strands hanging down as helices projected side-on: x = x0 + R sin(2π z / P), with R/P = curl_ratio."""
    h, w = size
    img = np.full((h, w, 3), background, np.uint8)
    rng = np.random.default_rng(seed)
    pitch = 40.0
    radius = curl_ratio * pitch
    z = np.arange(20, h - 20, 0.5)
    for x0 in np.linspace(50, w - 50, 9):
        phase = rng.uniform(0, 2 * np.pi)
        x = x0 + radius * np.sin(2 * np.pi * z / pitch + phase)
        pts = np.column_stack([x, z]).round().astype(np.int32)
        cv2.polylines(img, [pts], False, colour, thickness=2, lineType=cv2.LINE_AA)
    return img


def draw_side_on_helix(curl_ratio: float, *, pitch=80.0, size=(500, 300)):
    """One strand, x = x0 + R cos(2π z / P), drawn anti-aliased with sub-pixel vertices, 2 px thick."""
    h, w = size
    img = np.full((h, w, 3), 235, np.uint8)
    z = np.arange(10, h - 10, 0.25)
    x = w / 2 + curl_ratio * pitch * np.cos(2 * np.pi * z / pitch)
    pts = np.round(np.column_stack([x, z]) * 16).astype(np.int32)
    cv2.polylines(img, [pts], False, (60, 40, 20), thickness=2, lineType=cv2.LINE_AA, shift=4)
    return img


@pytest.mark.parametrize("curl_ratio", [0.05, 0.1, 0.2, 0.4, 0.8])
def test_gradient_ratio_of_a_side_on_helix_is_four_r_over_p(curl_ratio):
    # analytic: Σ|G_y| / Σ|G_x| = ∫|dx| / ∫|dz| = 4R per pitch P (controllers/vision.py docstring)
    img = draw_side_on_helix(curl_ratio)
    roi = (5, img.shape[0] - 5, 0, img.shape[1])
    assert gradient_ratio(img, roi=roi) == pytest.approx(4 * curl_ratio, rel=0.05)
    # so the clipped R_c of eq. 3.5 saturates from R/P = 1/4 on
    assert curliness(img, roi=roi) == pytest.approx(min(4 * curl_ratio, 1.0), rel=0.05)


def test_straight_hair_is_near_zero_and_curly_near_one():
    assert curliness(draw_hair(0.0), roi="auto") < 0.15
    assert curliness(draw_hair(0.8), roi="auto") > 0.6


def test_ranks_curl_ratios_and_is_robust_to_colour_and_light():
    ratios = [0.0, 0.1, 0.25, 0.4, 0.6, 0.8]
    for colour, bg in [((60, 40, 20), (235, 235, 235)), ((230, 200, 120), (40, 40, 60))]:
        rc = [
            np.mean(
                [curliness(draw_hair(r, seed=s, colour=colour, background=bg), roi="auto") for s in range(3)]
            )
            for r in ratios
        ]
        assert spearmanr(ratios, rc).statistic >= 0.9
    dark = (draw_hair(0.4).astype(np.float32) * 0.5).astype(np.uint8)  # half the light
    assert curliness(dark, roi="auto") == pytest.approx(curliness(draw_hair(0.4), roi="auto"), abs=0.05)


def test_signed_sums_cancel_so_magnitudes_are_used():
    gx, _gy = gradient_images(draw_hair(0.0))
    assert abs(gx.sum()) < 0.05 * np.abs(gx).sum()  # why eq. 3.5 needs |G|


def test_roi_and_bad_input():
    img = draw_hair(0.3)
    y0, y1, x0, x1 = hair_roi(img)
    assert 0 < y0 < 30 and img.shape[0] - 30 < y1 <= img.shape[0]
    assert 30 < x0 < 60 and img.shape[1] - 60 < x1 < img.shape[1] - 30  # strands span x = 50 ± R
    with pytest.raises(ValueError, match="image: expected"):
        curliness(np.zeros((4, 4, 5)))
    with pytest.raises(ValueError, match="roi"):
        curliness(img, roi=(0, 999, 0, 10))
    with pytest.raises(ValueError, match="no hair"):
        curliness(np.full((50, 50, 3), 200, np.uint8), roi="auto")
