"""Vision curliness metric R_c (thesis §3.3 "Vision pipeline", eq. 3.5).

The image is cropped to the hair, converted to greyscale, and differentiated with the Sobel operator. Straight
hanging hair has edges that run vertically, so its intensity changes across x (large G_x) far more than along y;
curly hair has edges in every direction, so the y gradients approach the x gradients. The ratio

    R_c = Σ|G_y| / Σ|G_x|, clipped to [0, 1]

is therefore ≈ 0 for straight and → 1 for curly hair, an image-based stand-in for R/P. Eq. 3.5 prints
|ΣG_y / ΣG_x| with *signed* gradients; summed over an image, signed gradients cancel (light-dark and dark-light
edges have opposite signs, and the sum telescopes to boundary differences), so we sum gradient **magnitudes**.

What the ratio measures. Along a thin dark curve the gradient is normal to the curve, so per unit length
|G_x| ∝ |cos θ| and |G_y| ∝ |sin θ| (θ from the vertical). Summed along the curve, Σ|G_y| / Σ|G_x| =
∫|dx| / ∫|dz|: horizontal over vertical travel. A helix of radius R and pitch P seen side-on projects to
x = R cos(2πz/P), which travels 4R sideways per pitch P, so the unclipped ratio is **4 R/P** and the clipped
R_c = min(4 R/P, 1). R_c therefore tracks R/P only up to R/P ≈ 1/4: every curlier helix reads R_c = 1, and eq. 3.5
cannot rank such wigs among themselves. :func:`gradient_ratio` returns the unclipped value, which keeps ranking
them as long as the image resolves the curls (``tests/controllers/test_vision.py`` checks the 4R/P law on drawn
curves; docs/policies.md, "Vision curliness", has the measurement on rendered wigs).
"""

from __future__ import annotations

import math

import cv2
import numpy as np

__all__ = ["curliness", "gradient_images", "gradient_ratio", "hair_roi"]


def _check_image(image) -> np.ndarray:
    img = np.asarray(image)
    if img.ndim not in (2, 3) or (img.ndim == 3 and img.shape[2] not in (1, 3, 4)):
        raise ValueError(f"image: expected an H×W or H×W×3 array, got shape {img.shape}")
    if img.shape[0] < 3 or img.shape[1] < 3:
        raise ValueError(f"image: too small for a 3×3 Sobel kernel, shape {img.shape}")
    if not np.all(np.isfinite(img)):
        raise ValueError("image: non-finite pixel values")
    return img


def _grey(img: np.ndarray) -> np.ndarray:
    img = img.astype(np.float32)
    if img.ndim == 3:
        img = cv2.cvtColor(img[..., :3], cv2.COLOR_RGB2GRAY)
    return img


def hair_roi(
    image, *, background=None, threshold: float = 12.0, margin: int = 2
) -> tuple[int, int, int, int]:
    """Bounding box ``(y0, y1, x0, x1)`` of the pixels that differ from the background.

    ``background`` is an image of the empty scene, or ``None`` to use the median colour of the image border (the
    webcam frames hair in front of a plain backdrop).
    """
    img = _check_image(image).astype(np.float32)
    if img.ndim == 2:
        img = img[..., None]
    if background is None:
        border = np.concatenate([img[0], img[-1], img[:, 0], img[:, -1]])
        bg = np.median(border, axis=0)
    else:
        bg = np.asarray(background, dtype=np.float32).reshape(
            img.shape if np.ndim(background) > 1 else (1, 1, -1)
        )
    diff = np.abs(img - bg).max(axis=-1)
    ys, xs = np.nonzero(diff > threshold)
    if ys.size == 0:
        raise ValueError("image: no hair found (the image matches the background)")
    h, w = diff.shape
    return (
        max(int(ys.min()) - margin, 0),
        min(int(ys.max()) + margin + 1, h),
        max(int(xs.min()) - margin, 0),
        min(int(xs.max()) + margin + 1, w),
    )


def gradient_images(image, *, roi=None) -> tuple[np.ndarray, np.ndarray]:
    """Sobel gradients ``(G_x, G_y)`` of the greyscale crop (3×3 kernel), as in thesis Fig. 3.4."""
    img = _check_image(image)
    if roi is not None:
        y0, y1, x0, x1 = (int(v) for v in roi)
        if not (0 <= y0 < y1 <= img.shape[0] and 0 <= x0 < x1 <= img.shape[1]):
            raise ValueError(f"roi: {roi!r} is outside the image of shape {img.shape[:2]}")
        img = img[y0:y1, x0:x1]
    grey = _grey(img)
    gx = cv2.Sobel(grey, cv2.CV_32F, 1, 0, ksize=3)
    gy = cv2.Sobel(grey, cv2.CV_32F, 0, 1, ksize=3)
    return gx, gy


def gradient_ratio(image, *, roi=None) -> float:
    """Unclipped Σ|G_y| / Σ|G_x| of the (cropped) image: 4 R/P for side-on helices (see the module docstring).

    ``roi`` as in :func:`curliness`. A flat image (no gradients) gives 0.
    """
    if isinstance(roi, str):
        if roi != "auto":
            raise ValueError(f"roi: expected (y0, y1, x0, x1), 'auto' or None, got {roi!r}")
        roi = hair_roi(image)
    gx, gy = gradient_images(image, roi=roi)
    sx = float(np.abs(gx).sum(dtype=np.float64))
    sy = float(np.abs(gy).sum(dtype=np.float64))
    if sx == 0.0:
        return math.inf if sy > 0.0 else 0.0
    return sy / sx


def curliness(image, *, roi=None) -> float:
    """Vision curliness R_c = Σ|G_y| / Σ|G_x| of the (cropped) image, clipped to [0, 1] (eq. 3.5).

    Parameters
    ----------
    image : H×W×3 (RGB) or H×W array
    roi : (y0, y1, x0, x1), "auto", or None
        Crop to the hair. The brushing envs give the rig's crop as ``env.unwrapped.hair_roi()``; ``"auto"`` uses
        :func:`hair_roi`, the bounding box of everything that differs from the border colour, which is the hair
        only when nothing else is in view.
    """
    return float(min(gradient_ratio(image, roi=roi), 1.0))
