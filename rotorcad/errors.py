"""The exceptions rotorcad raises for input it cannot accept: :class:`DesignError` and its family.

A :class:`DesignError` names the parameter, the allowed range and the value it got, so that
the command line can print it as one sentence and exit with status 2 (CONTRACT.md, common rules).
Three kinds are told apart by subclass, for a caller that handles them differently; each keeps the
sentence of its parent and is caught by ``except DesignError``:

* :class:`InputFileError` -- a file that cannot be read as what it should be (missing, special,
  oversized, binary, malformed), or a design file whose tables or keys are wrong;
* :class:`ToleranceError` -- a tolerance that cannot be met (a writer's fit, a sampling);
* :class:`GeometryError` -- values that are each allowed but describe no part: flanks that never
  meet, a mate generated from points that is no rotor;
* :class:`MissingValueError` -- a value given neither as an option nor in the design file.
"""

from __future__ import annotations


def limit_text(limit: float, value: object) -> str:
    """Write a limit with enough digits to differ from the refused value (6 significant at least).

    A value refused for missing its limit by less than the sixth digit would otherwise read as if
    it met it ("at least 63.2727 (got 63.2727272)").

    Parameters
    ----------
    limit : float
        The limit in the sentence.
    value : object
        The value given (a number; anything else gets 6 digits).

    Returns
    -------
    str
        ``f"{limit:.{n}g}"`` for the least n from 6 to 17 at which limit and value differ.
    """
    try:
        given = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return f"{limit:.6g}"
    for digits in range(6, 18):
        if f"{limit:.{digits}g}" != f"{given:.{digits}g}":
            return f"{limit:.{digits}g}"
    return repr(float(limit))


class DesignError(ValueError):
    """An input value or a combination of values that cannot describe a real part.

    A subclass of ``ValueError``; its message is :meth:`sentence` with the library's parameter name.

    Parameters
    ----------
    param : str
        The library's name of the offending parameter (the CLI maps it to its option name).
    allowed : str
        What is allowed, phrased to follow "must be", e.g. ``"an integer >= 3"``.
    value : object, optional
        The value that was given; None leaves "(got ...)" out of the sentence.
    detail : str, optional
        A further explanation appended after a colon.
    """

    def __init__(self, param: str, allowed: str, value: object = None, detail: str = "") -> None:
        self.param = param
        self.allowed = allowed
        self.value = value
        self.detail = detail
        super().__init__(self.sentence(param))

    def sentence(self, label: str | None = None) -> str:
        """Return the error as one sentence, naming the parameter as ``label``.

        Parameters
        ----------
        label : str, optional
            The name to show (an option name such as ``--teeth``); default the library's ``param``.

        Returns
        -------
        str
            ``"<label> must be <allowed> (got <value>): <detail>."``
        """
        label = label or self.param
        text = f"{label} must be {self.allowed}"
        if self.value is not None:
            text += f" (got {self.value})"
        if self.detail:
            text += f": {self.detail}"
        return text + "."


class InputFileError(DesignError):
    """A file that cannot be read as what it should be, or a design file with wrong tables or keys.

    A missing, special (FIFO, device, folder), oversized, binary or malformed file, or a table or
    key of a design that is unknown, of the wrong type or missing; ``param`` names the option or
    ``[table] key`` that gave it.
    """


class ToleranceError(DesignError):
    """A tolerance that cannot be met: the result would be farther from the exact geometry than asked."""


class GeometryError(DesignError):
    """Values that are each allowed but together describe no part (e.g. gear flanks that never meet)."""


class MissingValueError(DesignError):
    """A value that must be given, as an option or in the design file, and is given by neither.

    Its sentence names the library's parameter; the command line says which option (or design
    key) gives it.
    """

    def __init__(self, param: str, allowed: str = "given", value: object = None, detail: str = "missing") -> None:
        super().__init__(param, allowed, value, detail)


class InputNote(UserWarning):
    """Something rotorcad did to the input that the user should know of.

    E.g. a DXF outline closed across a gap within the stated accuracy; the command line prints it
    as one line ``rotorcad: note: ...`` on stderr after a successful run.
    """
