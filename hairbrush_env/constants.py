"""Numbers the whole package shares: the thesis's pain threshold and finish tolerance, the load cell's capacity, the
webcam resolution. Defined once here; modules import them (``controllers/`` too) instead of repeating them."""

from __future__ import annotations

#: Pain threshold of the thesis (chapter 3, Algorithm 1): F_T ≈ 10 N.
PAIN_THRESHOLD_N = 10.0
#: Thesis eq. 3.4: brushing is finished when consecutive full strokes' maximum forces differ by less than this [N].
FINISH_FORCE_TOLERANCE_N = 0.4
#: Rated capacity of the simulated load cell [N]: readings saturate here, which bounds the observation spaces.
LOAD_CELL_CAPACITY_N = 100.0
#: Webcam resolution at which the vision R_c ranks every preset (docs/policies.md, "Vision curliness").
WEBCAM_SIZE = (640, 480)
