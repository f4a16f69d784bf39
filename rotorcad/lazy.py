"""Names of a package imported on first use (PEP 562).

So that importing a light module of a package does not load its heavy neighbours.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable


def lazy_names(package: str, api: dict[str, str]) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """Make a package's module ``__getattr__``, ``__dir__`` and ``__all__`` for names of its modules.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    api : dict of str to str
        Each public name and the module that defines it.

    Returns
    -------
    getattr, dir, all
        Assign them to ``__getattr__, __dir__, __all__`` in the package's ``__init__``.

    Examples
    --------
    >>> get, names, public = lazy_names("rotorcad.gears", {"inv": "rotorcad.gears.formulas"})
    >>> round(get("inv")(0.5), 6)
    0.046302
    >>> public
    ['inv']
    """

    def attribute(name: str) -> object:
        if name in api:
            return getattr(importlib.import_module(api[name]), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def names() -> list[str]:
        return sorted([*vars(sys.modules[package]), *api])

    return attribute, names, sorted(api)
