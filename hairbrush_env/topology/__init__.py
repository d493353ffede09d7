"""Exact, vectorized curve topology for polylines (pure numpy/numba; imports nothing else of the project).

Curves are ``(N, 3)`` float arrays of vertices. Quantities (thesis chapter 1, eqs 1.15–1.18; chapter 4, eq. 4.1):

- :func:`linking_number`, :func:`writhe`, :func:`average_crossing_number` — exact segment-pair Gauss sums;
- :func:`twist` — ribbon twist by parallel transport (so that Lk = Tw + Wr, eq. 1.17);
- :func:`link_density`, :func:`link_current` — link per unit length λ(s) and dLk/dx (chapter 2);
- :func:`interaction_census` — N-body interactions per unit length of a bundle (Fig. 2.1, 2.5);
  :func:`empirical_lk_threshold` — the thesis's rule for the link criterion's threshold;
- :mod:`.helix` — helices, double helices, analytic twist/writhe and Love's helix mechanics.
"""

from .census import (
    clip_to_slab,
    empirical_lk_threshold,
    interaction_census,
    layer_link_matrices,
    link_census_from_matrices,
)
from .gauss import (
    TopologyWarning,
    average_crossing_number,
    link_current,
    link_density,
    linking_number,
    pair_gauss_matrix,
    writhe,
)
from .helix import (
    double_helix,
    helix,
    helix_arclength,
    helix_twist_writhe,
    love_helix_load,
    love_small_extension,
    love_tine_force,
    pitch_angle,
)
from .ribbon import parallel_transport, twist

__all__ = [
    "TopologyWarning",
    "average_crossing_number",
    "clip_to_slab",
    "double_helix",
    "empirical_lk_threshold",
    "helix",
    "helix_arclength",
    "helix_twist_writhe",
    "interaction_census",
    "layer_link_matrices",
    "link_census_from_matrices",
    "link_current",
    "link_density",
    "linking_number",
    "love_helix_load",
    "love_small_extension",
    "love_tine_force",
    "pair_gauss_matrix",
    "parallel_transport",
    "pitch_angle",
    "twist",
    "writhe",
]
