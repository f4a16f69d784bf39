"""What ``exports`` adds to the core's extension points (:mod:`rotorcad.extensions`).

The readers of a points family's file (CSV points or a DXF drawing), so that the core can read the
base design of a sweep file without importing ``exports``. Imported by the command line, or
through the entry point ``exports`` of the group ``rotorcad.extensions``.
"""

from __future__ import annotations

from exports.dxf_profile import read_profile, read_profile_points
from rotorcad.extensions import register_profile_reader

register_profile_reader("rack-points", read_profile_points)
register_profile_reader("male-points", read_profile)
register_profile_reader("female-points", read_profile)
