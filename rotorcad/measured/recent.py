"""A memo of a function's last few results on numpy-array arguments (the same inputs, the same result).

For a step of the measured-outline pipeline that two stages run on the same points (the corners of
an outline located by :func:`rotorcad.measured.fit.lobe_pieces` and again by
:func:`rotorcad.measured.fit.tangent_spread`): the arguments are compared by value (arrays by dtype,
shape and bytes), the result handed back as a copy so that no caller changes another's.
"""

from __future__ import annotations

import functools
import threading
from collections import OrderedDict
from collections.abc import Callable
from typing import Any

import numpy as np


def _key(value: Any) -> Any:
    """Return a hashable stand-in for one argument: an array by its dtype, shape and bytes, else itself."""
    if isinstance(value, np.ndarray):
        return (value.dtype.str, value.shape, value.tobytes())
    return value


def recent_results(size: int = 4) -> Callable[[Callable[..., np.ndarray]], Callable[..., np.ndarray]]:
    """Decorate a function of arrays and hashable values returning an array: its last ``size`` results kept.

    Parameters
    ----------
    size : int
        How many distinct calls are remembered (the oldest is forgotten first).

    Returns
    -------
    callable
        The decorator; the decorated function returns a copy of the remembered array.
    """

    def decorate(function: Callable[..., np.ndarray]) -> Callable[..., np.ndarray]:
        kept: OrderedDict[Any, np.ndarray] = OrderedDict()
        lock = threading.Lock()  # the dict only: a sweep's threads may call at once

        @functools.wraps(function)
        def remembered(*args: Any, **kwargs: Any) -> np.ndarray:
            key = (tuple(_key(a) for a in args), tuple(sorted((k, _key(v)) for k, v in kwargs.items())))
            with lock:
                result = kept.get(key)
            if result is None:
                result = function(*args, **kwargs)
                with lock:
                    kept[key] = result
                    while len(kept) > size:
                        kept.popitem(last=False)
            return np.array(result, copy=True)

        return remembered

    return decorate
