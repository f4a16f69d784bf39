"""Roles as types: which rotor, and what a piece of a profile or rack does.

Decisions are taken on these values, never on names (a segment may be renamed freely) or on
strings compared in place. ``Side`` is a ``StrEnum``: ``Side("male")`` reads what a user or a file
gives, a ``Side`` prints as its text ("male") and compares equal to it where a caller still passes one.
"""

from __future__ import annotations

from enum import Enum, StrEnum


class Side(StrEnum):
    """Rotor 1, the male (main, Hauptläufer), or rotor 2, the female (gate, Nebenläufer)."""

    MALE = "male"
    FEMALE = "female"

    @property
    def other(self) -> Side:
        """The mating rotor."""
        return Side.FEMALE if self is Side.MALE else Side.MALE

    def pick(self, male: object, female: object) -> object:
        """Return the value of this rotor from a pair of per-rotor values.

        Parameters
        ----------
        male, female : object
            The male's and the female's value.

        Returns
        -------
        object
            ``male`` for :attr:`Side.MALE`, ``female`` for :attr:`Side.FEMALE`.
        """
        return male if self is Side.MALE else female


class EndFace(StrEnum):
    """The end face of a screw rotor pair a transverse section is seen from.

    rotorcad's sections are seen from the suction end (the male turns counter-clockwise there); a
    section seen from the discharge end is their mirror image (:mod:`rotorcad.measured.end_face`).
    """

    SUCTION = "suction"
    DISCHARGE = "discharge"


class PieceRole(Enum):
    """What a piece of a rack chain or of a derived rack does.

    CURVE generates a curve on both rotors; a corner path is the path of one rotor's sharp corner
    (it generates only that corner on its own rotor, and a point-generated flank on the other); a
    corner fan is the zero-radius arc inserted at a profile's corner by inverse generation (its rack
    image is the corner's path: it does not cut a hob's flank).
    """

    CURVE = "curve"
    MALE_CORNER_PATH = "male corner path"
    FEMALE_CORNER_PATH = "female corner path"
    CORNER_FAN = "corner fan"

    @staticmethod
    def corner_path_of(side: Side) -> PieceRole:
        """Return the corner-path role of ``side``'s corner.

        Parameters
        ----------
        side : Side or str
            The rotor whose sharp corner traces the path (``"male"`` or ``"female"`` are read too).

        Returns
        -------
        PieceRole
            :attr:`MALE_CORNER_PATH` or :attr:`FEMALE_CORNER_PATH`.
        """
        return PieceRole.MALE_CORNER_PATH if Side(side) is Side.MALE else PieceRole.FEMALE_CORNER_PATH


class Flank(StrEnum):
    """Which part of a lobe a contact belongs to (Rinder sec. 1.2), read off the rack's geometry.

    Along the rack chain (travelled in the direction of motion) the male lobe's trailing flank
    rises towards the male tip: the driving flank (Triebflanke); its leading flank falls from it
    towards the housing cusp: the sealing flank (Dichtflanke). TIP is the male tip land (on the
    female root), ROOT the male root land (under the female tip).
    """

    DRIVING = "driving"
    SEALING = "sealing"
    TIP = "tip"
    ROOT = "root"


class ToothFlank(StrEnum):
    """The left or the right flank of a tooth (ISO 1328-1:2013, 3.1.4), as an inspection reports it.

    Seen from the reference face (rotorcad: from +z, the drawing's view) with the tooth's tip
    pointing up: the left flank is on the left. For tooth 0 of a gear (centred on +x, CONTRACT.md)
    the left flank is the one on the counter-clockwise side (y > 0), the right flank the clockwise one.
    """

    LEFT = "left"
    RIGHT = "right"

    @property
    def sign(self) -> int:
        """+1 for the left (counter-clockwise) flank, -1 for the right one: the direction of its outward normal."""
        return 1 if self is ToothFlank.LEFT else -1


__all__ = ["EndFace", "Flank", "PieceRole", "Side", "ToothFlank"]
