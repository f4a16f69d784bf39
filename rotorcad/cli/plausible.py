"""Say the plausibility warnings of the core (:mod:`rotorcad.design.plausibility`) on stderr.

A warning is not a refusal: the value is legal and the command runs; the line is said before the
work starts (a long run shows at once why its figures may be off), on stderr only (``--json`` stays
one object on stdout), as ``rotorcad: warning: SENTENCE.`` (CONTRACT.md, "Plausibility").
"""

from __future__ import annotations

from collections.abc import Iterable

import click

SAID: list[str] = []
"""Every warning said in this process, in order (for the tests)."""


def say_warnings(sentences: Iterable[str]) -> None:
    """Write each sentence (without its final stop) once as ``rotorcad: warning: ...`` on stderr.

    Parameters
    ----------
    sentences : iterable of str
        From :func:`rotorcad.design.plausibility.module_warnings` and the like.
    """
    for sentence in dict.fromkeys(sentences):
        SAID.append(sentence)
        click.echo(f"rotorcad: warning: {sentence}.", err=True)


__all__ = ["SAID", "say_warnings"]
