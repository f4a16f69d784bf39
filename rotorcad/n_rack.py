"""Old import path of Stosic's N rack: it now lives in :mod:`rotorcad.families.n_rack`.

Kept so that ``from rotorcad.n_rack import n_rack`` goes on working.
"""

from __future__ import annotations

from rotorcad.families.n_rack import n_rack, sealing_contact

__all__ = ["n_rack", "sealing_contact"]
