"""Old import path of Stosic's N rack: it now lives in :mod:`rotorcad.families.n_rack`.

Kept so that ``from rotorcad.n_rack import n_rack`` goes on working; new code imports from
:mod:`rotorcad.families.n_rack`. Importing this module makes ``rotorcad.n_rack`` (the lazy public
name of the builder) this module for the rest of the process, as any submodule of that name would.
"""

from __future__ import annotations

from rotorcad.families.n_rack import n_rack, sealing_contact

__all__ = ["n_rack", "sealing_contact"]
