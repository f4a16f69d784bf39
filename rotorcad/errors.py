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
* :class:`ConflictError` -- values that are each allowed but conflict with one another (a tip
  radius and a root radius over the centre distance), said of each of them in turn, so that a
  command names the one the user typed;
* :class:`MissingValueError` -- a value given neither as an option nor in the design file.
"""

from __future__ import annotations

import re

_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def value_text(value: object, context: str = "") -> str:
    """Write a refused value as a sentence shows it: a float with 6 significant digits, more if needed.

    A float is written with the fewest digits from 6 to 17 at which it lies on the same side of every
    number in ``context`` as the value itself (the allowed range: "at most 36 mm (got 36.0000004)"),
    so that the sentence never shows a refused value equal to its limit, or on its other side. Anything else (a whole number, a
    string, a bool, an array) as ``str``.

    Parameters
    ----------
    value : object
        The value given.
    context : str
        The text the value is read against (the sentence's allowed range).

    Returns
    -------
    str
        E.g. ``46.4893`` for ``46.48933484382849`` (was written in full, 16 digits).
    """
    dtype = getattr(value, "dtype", None)  # a numpy scalar (numpy's float64 is a float too)
    is_float = isinstance(value, float) or (getattr(dtype, "kind", "") == "f" and getattr(value, "shape", None) == ())
    if not is_float:
        return str(value)
    v = float(value)  # type: ignore[arg-type]
    if v != v or v in (float("inf"), float("-inf")):
        return str(v)
    numbers = set()
    for token in _NUMBER.findall(context):
        try:
            numbers.add(float(token))
        except ValueError:  # pragma: no cover - the pattern reads only numbers
            pass

    def side(x: float, c: float) -> int:
        return (x > c) - (x < c)

    for digits in range(6, 18):
        text = f"{v:.{digits}g}"
        if all(side(float(text), c) == side(v, c) for c in numbers):
            return text
    return repr(v)


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
            text += f" (got {value_text(self.value, self.allowed)})"
        if self.detail:
            text += f": {self.detail}"
        return text + "."


class ConflictError(DesignError):
    """Values that are each allowed but conflict with one another, one of them named.

    The library names one of the values in conflict (``param``); ``alternatives`` holds the same
    conflict said of each of the others (their own allowed range and value), so that a caller that
    knows which value the user typed (an option beside a design file) names that one
    (``--male-tip-radius must be at most ...`` rather than the design's ``[pair] female_root_radius``).

    Parameters
    ----------
    param, allowed, value, detail
        As :class:`DesignError`, for the value the library names.
    alternatives : tuple of DesignError
        The same conflict named by each other value in it.
    """

    def __init__(
        self, param: str, allowed: str, value: object = None, detail: str = "", alternatives: tuple[DesignError, ...] = ()
    ) -> None:
        super().__init__(param, allowed, value, detail)
        self.alternatives = alternatives

    def named_by(self, typed: object) -> DesignError:
        """Return the conflict said of a value the user typed, when the named one is not.

        Parameters
        ----------
        typed : collection of str
            The library names of the values the user typed (options), as opposed to a design file's.

        Returns
        -------
        DesignError
            Itself when ``param`` was typed or none of the others was; else the first alternative
            whose value was typed.
        """
        if self.param in typed:  # type: ignore[operator]
            return self
        return next((alt for alt in self.alternatives if alt.param in typed), self)  # type: ignore[operator]


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
