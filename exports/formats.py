"""The export formats: one table of what ``rotorcad export`` writes, filled by the writer modules.

Each writer module declares its row(s) with :func:`register`: the format's name (``--format``), the
file name's ending, the function that plans one body's file, the tolerance the file meets and
how, the limits that refuse a file too large, and whether it is written in the background
process (:mod:`exports.background`). ``rotorcad export`` (and the gear export) is one loop over
placed bodies (:mod:`rotorcad.assembly`) and these rows (:func:`plan_files`).

The built-in rows, the tolerance each file meets and how:

- ``stl``, ``stl-ascii``, ``3mf``, ``obj``, ``ply``, ``glb``, ``vtu``, ``xdmf``
  (:mod:`exports.meshes`): the surface tolerance asked, by the swept solid's layers and the
  section's chords (the row gives the solid's own); the housing's, the sag of the bores' chords.
- ``dxf``, ``dxf-r12`` (:mod:`exports.dxf`, in the worker): the section's chords, half the
  tolerance (a quarter for a gear).
- ``dxf-mesh``, ``dxf-mesh-r12`` (:mod:`exports.dxf`): as the meshes; at most 50 000 triangles.
- ``step`` (:mod:`exports.step`, in the worker): min(tolerance, 1 µm), measured on the solid's
  faces against the helicoid and refused when not met; the housing exact (box and cylinders).
- ``step-faceted`` (:mod:`exports.step`): as the meshes; at most 20 000 facets.
- ``csv`` (:mod:`exports.csv_points`): the section's chords, in the body's own frame.

Adding a format is one writer, one row and one test (README.md, developer section)::

    def plan_xyz(fmt, body, tolerance, row):
        row.update(triangles=0, volume=body.section_volume, tolerance=body.section_tolerance)
        points = body.placed_points()
        return lambda path: np.savetxt(path, points)

    register(ExportFormat("xyz", "_section.xyz", plan_xyz, "the section's chords", meshes=False))
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from exports.background import BackgroundWriter
from rotorcad.assembly import BodyKind, PlacedBody
from rotorcad.errors import DesignError

EVERY_BODY = frozenset(BodyKind)
SWEPT_BODIES = frozenset({BodyKind.ROTOR, BodyKind.GEAR})
WRITER_MODULES = ("exports.meshes", "exports.dxf", "exports.step", "exports.csv_points")
"""The modules whose rows make the built-in table, in the order the formats are listed."""


@dataclass(frozen=True)
class Limit:
    """The most triangles a format's file may hold, and how to say so.

    Parameters
    ----------
    triangles : int
        Most triangles (facets) of one body's file.
    what : str
        The file as the refusal names it (``"a DXF mesh"``).
    alternative : str
        A further clause of the refusal pointing to another format ("; --format step ...").
    """

    triangles: int
    what: str
    alternative: str = ""


Writer = Callable[[Path], Any] | BackgroundWriter
"""Writes one (temporary) file: ``write(path)`` here, or a :class:`BackgroundWriter` the worker may run."""

Planner = Callable[["ExportFormat", PlacedBody, float, dict[str, Any]], Writer]
"""``plan(fmt, body, tolerance, row)``: fills in the row what is known before writing (``triangles``,
``volume`` mm³, ``tolerance`` mm, ``faces``) and returns the writer, which may fill in what it
measures (a mesh's triangles, a STEP's deviation)."""


@dataclass(frozen=True)
class ExportFormat:
    """One row of the format table.

    Parameters
    ----------
    name : str
        The ``--format`` name (lower case).
    extension : str
        Ending of the file name after ``<design>_<body>`` (``".stl"``, ``"_ascii.stl"``); unique.
    plan : callable
        ``plan(fmt, body, tolerance, row)`` -> the writer of one placed body's file at the surface
        tolerance asked (mm), filling ``row`` (:data:`Planner`).
    tolerance : str
        The tolerance the file meets and how, in words (this module's table).
    bodies : frozenset of BodyKind
        The bodies it writes; the others are left out (the housing has no drawing).
    limit : Limit, optional
        The most triangles of a file, refused before any sweep when the estimate is twice over
        and when the mesh is over (:func:`check_limits`).
    background : bool
        Its writer may run in the worker process.
    preload : tuple of str
        Modules the worker imports when it starts (``"ezdxf"``), when this format is asked.
    kind_extensions : tuple of (BodyKind, str)
        Endings for a kind of body where they differ from ``extension`` (a gear's points file keeps
        the name ``<design>_<body>.csv`` it has always had).
    meshes : bool
        Its writer triangulates the swept solid (:func:`meshed`), so that the triangles the surface
        tolerance asks must fit in memory (:func:`makes_meshes`); False for the files made from the
        exact curves or the section (``step``, ``dxf``, ``csv``), whose size does not grow with the
        triangles (a new user's STEP-only export at ``--tolerance 0.001`` was refused for 10.7
        million triangles no file would hold).
    """

    name: str
    extension: str
    plan: Planner
    tolerance: str
    bodies: frozenset[BodyKind] = field(default=EVERY_BODY)
    limit: Limit | None = None
    background: bool = False
    preload: tuple[str, ...] = ()
    kind_extensions: tuple[tuple[BodyKind, str], ...] = ()
    meshes: bool = True

    def ending(self, kind: BodyKind) -> str:
        """Return the file ending after ``<design>_<body>`` for a body of ``kind``."""
        return dict(self.kind_extensions).get(kind, self.extension)


_TABLE: dict[str, ExportFormat] = {}


class RefusalError(DesignError):
    """A file that cannot be written as asked, said in one sentence of its own."""

    def __init__(self, text: str) -> None:
        ValueError.__init__(self, text)
        self.param, self.allowed, self.value, self.detail = "", "", None, ""
        self.text = text

    def sentence(self, label: str | None = None) -> str:
        """Return the sentence (``label`` is not used: the text names what it refuses)."""
        return self.text


def register(fmt: ExportFormat) -> ExportFormat:
    """Add a row to the table (a writer module calls this when imported).

    Raises
    ------
    ValueError
        A name or an extension that another row has (two formats would write one file).
    """
    for other in _TABLE.values():
        if other.name != fmt.name and (other.extension == fmt.extension):
            raise ValueError(f"format {fmt.name!r}: extension {fmt.extension!r} is {other.name!r}'s")
    if fmt.name in _TABLE and _TABLE[fmt.name] != fmt:
        raise ValueError(f"format {fmt.name!r} is in the table already")
    _TABLE[fmt.name] = fmt
    return fmt


def unregister(name: str) -> None:
    """Remove a row (a test's toy format)."""
    _TABLE.pop(name, None)


def table() -> dict[str, ExportFormat]:
    """Return the table, name -> row: the built-in writers' rows first, in :data:`WRITER_MODULES` order.

    Whatever order the writer modules were imported in; rows registered elsewhere follow, in the
    order they were registered.
    """
    for module in WRITER_MODULES:
        importlib.import_module(module)
    rank = {module: i for i, module in enumerate(WRITER_MODULES)}
    ordered = sorted(_TABLE.values(), key=lambda f: rank.get(f.plan.__module__, len(rank)))  # stable: rows in order
    return {f.name: f for f in ordered}


def names(kind: BodyKind | None = None) -> tuple[str, ...]:
    """Return the format names, all or those that write bodies of ``kind``."""
    return tuple(n for n, f in table().items() if kind is None or kind in f.bodies)


def preload(fmts: Iterable[ExportFormat]) -> tuple[str, ...]:
    """Return the modules the worker process should import for ``fmts`` (those installed; empty: no worker needed)."""
    import importlib.util

    wanted = dict.fromkeys(m for f in fmts if f.background for m in f.preload)
    return tuple(m for m in wanted if importlib.util.find_spec(m.split(".")[0]) is not None)


def refuse_mesh_size(
    fmt: ExportFormat, body: PlacedBody, triangles: float, tolerance: float, needed: float | None = None
) -> None:
    """Refuse a file of too many triangles, naming the tolerance that would do.

    A file coarser than the tolerance asked is never written (once a faceted STEP was written at
    3.1 mm where 5 µm were asked).

    Raises
    ------
    DesignError
        Always, naming ``--tolerance``.
    """
    limit = fmt.limit
    needed = body.coarser_tolerance(tolerance, limit.triangles) if needed is None else needed
    can = f"{needed:.3g} mm or coarser would do" if needed <= 1.0 else f"only {needed:.3g} mm would, above the 1 mm allowed"
    raise DesignError(
        "--tolerance",
        f"coarser for {limit.what} of the {body.name} (about {triangles:.3g} triangles; at most {limit.triangles})",
        detail=can + limit.alternative,
    )


def meshed(fmt: ExportFormat, body: PlacedBody, tolerance: float, row: dict[str, Any]):
    """Return the body's mesh for a file of ``fmt``, refused when over the format's limit; fill ``row``.

    Returns
    -------
    MeshedBody
        The mesh, its volume and the tolerance it was made to (written into ``row``).
    """
    made = body.mesh(tolerance)
    faces = len(made.mesh.faces)
    if fmt.limit is not None and body.swept and faces > fmt.limit.triangles:
        refuse_mesh_size(fmt, body, faces, tolerance)
    row.update(triangles=faces, volume=made.volume, tolerance=made.tolerance)
    return made


def makes_meshes(fmts: Iterable[ExportFormat]) -> bool:
    """Tell whether any of the formats triangulates the swept solids (:attr:`ExportFormat.meshes`).

    Only then is a request refused for triangles that would not fit in memory
    (:func:`rotorcad.assembly.check_solid_work`).
    """
    return any(fmt.meshes for fmt in fmts)


def check_limits(fmts: Iterable[ExportFormat], bodies: Iterable[PlacedBody], tolerance: float) -> None:
    """Refuse, before any solid is swept, a file whose estimated triangles are twice its format's limit.

    Raises
    ------
    DesignError
        :func:`refuse_mesh_size`.
    """
    bodies = list(bodies)
    for fmt in fmts:
        if fmt.limit is None:
            continue
        limit = fmt.limit.triangles
        estimates = [(body, body.estimated_triangles(tolerance)) for body in bodies if body.swept and body.kind in fmt.bodies]
        if any(estimate > 2 * limit for _, estimate in estimates):
            # the tolerance named must do for every body of the file set: the coarsest any body over the limit needs
            over = [
                (body, estimate, body.coarser_tolerance(tolerance, limit)) for body, estimate in estimates if estimate > limit
            ]
            body, estimate, needed = max(over, key=lambda b: b[2])
            refuse_mesh_size(fmt, body, estimate, tolerance, needed)


def plan_files(
    fmts: Iterable[ExportFormat], bodies: Iterable[PlacedBody], tolerance: float, folder: Path, stem: str
) -> list[tuple[Path, dict[str, Any], Writer]]:
    """Plan every body's file in every format that writes it: the one loop of an export.

    Returns
    -------
    list of (Path, dict, writer)
        The file ``<folder>/<stem>_<body><extension>``, its row (``path``, ``format``, ``body``,
        then the format's figures, filled further by the writer) and its writer.
    """
    fmts = list(fmts)
    planned = []
    for body in bodies:
        for fmt in (f for f in fmts if body.kind in f.bodies):
            path = folder / f"{stem}_{body.name}{fmt.ending(body.kind)}"
            row: dict[str, Any] = {"path": str(path), "format": fmt.name, "body": body.name}
            planned.append((path, row, fmt.plan(fmt, body, tolerance, row)))
    return planned
