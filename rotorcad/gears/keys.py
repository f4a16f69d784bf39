"""Parallel keys and keyways by DIN 6885-1 (drive-type feather keys, high form).

One row per key size: the bore (shaft) diameters it is for, over ``bore_over`` up to ``bore_to``,
the key's width b and height h, the keyway depth in the shaft t1 and in the hub t2 (the hub's
keyway bottom lies d + t2 from the opposite side of the bore, so d/2 + t2 from the axis). Values of
DIN 6885-1:1968, table 1 (the same key sections as ISO/R 773), 6 to 500 mm.
"""

from __future__ import annotations

from dataclasses import dataclass

from rotorcad.errors import DesignError


@dataclass(frozen=True)
class ParallelKey:
    """One row of DIN 6885-1.

    Attributes
    ----------
    bore_over, bore_to : float, mm
        The bore diameters d of the row: bore_over < d <= bore_to.
    width, height : float, mm
        The key's b x h.
    shaft_depth, hub_depth : float, mm
        The keyway depths t1 (shaft) and t2 (hub).
    """

    bore_over: float
    bore_to: float
    width: float
    height: float
    shaft_depth: float
    hub_depth: float


_ROWS = (
    # d over, d to, b, h, t1, t2
    (6, 8, 2, 2, 1.2, 1.0),
    (8, 10, 3, 3, 1.8, 1.4),
    (10, 12, 4, 4, 2.5, 1.8),
    (12, 17, 5, 5, 3.0, 2.3),
    (17, 22, 6, 6, 3.5, 2.8),
    (22, 30, 8, 7, 4.0, 3.3),
    (30, 38, 10, 8, 5.0, 3.3),
    (38, 44, 12, 8, 5.0, 3.3),
    (44, 50, 14, 9, 5.5, 3.8),
    (50, 58, 16, 10, 6.0, 4.3),
    (58, 65, 18, 11, 7.0, 4.4),
    (65, 75, 20, 12, 7.5, 4.9),
    (75, 85, 22, 14, 9.0, 5.4),
    (85, 95, 25, 14, 9.0, 5.4),
    (95, 110, 28, 16, 10.0, 6.4),
    (110, 130, 32, 18, 11.0, 7.4),
    (130, 150, 36, 20, 12.0, 8.4),
    (150, 170, 40, 22, 13.0, 9.4),
    (170, 200, 45, 25, 15.0, 10.4),
    (200, 230, 50, 28, 17.0, 11.4),
    (230, 260, 56, 32, 20.0, 12.4),
    (260, 290, 63, 32, 20.0, 12.4),
    (290, 330, 70, 36, 22.0, 14.4),
    (330, 380, 80, 40, 25.0, 15.4),
    (380, 440, 90, 45, 28.0, 17.4),
    (440, 500, 100, 50, 31.0, 19.5),
)

DIN_6885_1: tuple[ParallelKey, ...] = tuple(ParallelKey(*map(float, row)) for row in _ROWS)
"""The rows of DIN 6885-1, by increasing bore."""

BORE_RANGE = (DIN_6885_1[0].bore_over, DIN_6885_1[-1].bore_to)
"""Bores DIN 6885-1 gives a key for, mm: over 6 up to 500."""


def key_for_bore(bore: float) -> ParallelKey:
    """Return the DIN 6885-1 key of a bore diameter.

    Parameters
    ----------
    bore : float, mm
        The bore (shaft) diameter d.

    Returns
    -------
    ParallelKey
        The row with bore_over < d <= bore_to.

    Raises
    ------
    DesignError
        ``keyway`` for a bore outside 6 < d <= 500 mm (DIN 6885-1 has no key for it).
    """
    for row in DIN_6885_1:
        if row.bore_over < bore <= row.bore_to:
            return row
    raise DesignError(
        "keyway",
        f"false for a bore of {bore:g} mm: DIN 6885-1 gives keys for bores over {BORE_RANGE[0]:g} up to {BORE_RANGE[1]:g} mm",
    )


__all__ = ["BORE_RANGE", "DIN_6885_1", "ParallelKey", "key_for_bore"]
