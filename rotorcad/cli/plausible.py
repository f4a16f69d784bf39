"""Say the plausibility warnings of the core (:mod:`rotorcad.design.plausibility`) on stderr.

A warning is not a refusal: the value is legal and the command runs. Each sentence is raised as a
:class:`rotorcad.design.plausibility.UnitWarning`, which the command line prints after a successful
run as ``rotorcad: warning: SENTENCE.`` on stderr (``--json`` stays one object on stdout), and not at
all when the run ends in a refusal, which stays one sentence (CONTRACT.md, "Plausibility").
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable

SAID: list[str] = []
"""Every warning raised in this process, in order (for the tests)."""


def say_warnings(sentences: Iterable[str]) -> None:
    """Raise each sentence (without its final stop) once as a :class:`~rotorcad.design.plausibility.UnitWarning`.

    Parameters
    ----------
    sentences : iterable of str
        From :func:`rotorcad.design.plausibility.module_warnings` and the like.
    """
    from rotorcad.design.plausibility import UnitWarning

    for sentence in dict.fromkeys(sentences):
        SAID.append(sentence)
        warnings.warn(sentence, UnitWarning, stacklevel=2)


__all__ = ["SAID", "say_warnings"]
