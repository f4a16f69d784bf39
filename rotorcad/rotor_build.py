"""Old path of a rotor pair built from a design: it moved to :mod:`rotorcad.design.rotors` (kept for a while)."""

from rotorcad.design.rotors import (  # noqa: F401 - re-exported
    LOBE_POINTS_FACTOR,
    MAX_LOBE_POINTS,
    PAIR_DEFAULTS,
    SPEED_DEFAULT,
    PairSpec,
    analyse_pair,
    build_pair,
    design_summary,
    merge_pair,
    pair_spec,
    smooth_lobe_points,
)
