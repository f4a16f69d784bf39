"""Exact STEP of an internal gear: the cylinder of its outer diameter minus its swept toothed bore.

The bore is swept from the exact section segments as the gears' and rotors' solids are
(:func:`exports.step_exact.helical_solid`: one B-spline face per piece of the bore), checked against
the exact helicoid (:func:`exports.step_exact.helicoid_deviation`), and cut from an OpenCASCADE
cylinder; the outer face is an exact cylinder.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np


def ring_solid(sections: list, lead: float, length: float, outer_radius: float, tolerance: float, exact: np.ndarray):
    """Return the ring solid and the deviation of its bore from the helicoid, mm.

    Parameters
    ----------
    sections : list of lists of SectionSegment
        The bore (counter-clockwise) sampled ever finer (:func:`exports.step_exact.section_segments`);
        the first whose swept faces are within ``tolerance`` of the helicoid is used.
    lead : float, mm
        Signed lead (inf: a spur gear).
    length : float, mm
        Face width.
    outer_radius : float, mm
        The ring's outer radius.
    tolerance : float, mm
        Largest deviation of the bore's faces from the helicoid.
    exact : (n, 2) float array, mm
        The bore as a fine closed polyline.

    Returns
    -------
    (OCP.TopoDS.TopoDS_Shape, float)

    Raises
    ------
    exports.step_exact.StepDeviationError
        When even the finest section's faces stray beyond ``tolerance``.
    """
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder

    from exports.step_exact import StepDeviationError, helical_solid, helicoid_deviation

    for i, segments in enumerate(sections):
        bore = helical_solid(segments, lead, length, tolerance)
        dev = helicoid_deviation(bore, exact, lead, length)
        if dev <= tolerance:
            break
        if i == len(sections) - 1:
            raise StepDeviationError(
                f"the STEP bore is {dev * 1e3:.2f} um from the helicoid, more than the tolerance {tolerance * 1e3:g} um"
            )
    cut = BRepAlgoAPI_Cut(BRepPrimAPI_MakeCylinder(float(outer_radius), float(length)).Shape(), bore)
    cut.Build()
    if not cut.IsDone():
        raise ValueError("OpenCASCADE could not cut the bore from the ring's cylinder")
    return cut.Shape(), float(dev)


def write_ring_step(
    path: Path,
    sections: list,
    lead: float,
    length: float,
    outer_radius: float,
    tolerance: float,
    body: str,
    offset: tuple[float, float],
    exact: np.ndarray,
) -> dict[str, float]:
    """Write an internal gear as STEP (AP214, product named ``body``): :func:`ring_solid`, translated by ``offset``.

    Returns
    -------
    dict of float
        ``faces`` and ``deviation`` (mm, the bore's faces from the helicoid).
    """
    from exports.step_exact import faces, write_shape

    shape, dev = ring_solid(sections, lead, length, outer_radius, tolerance, exact)
    write_shape(path, shape, body, tuple(offset))
    return {"faces": float(len(faces(shape))), "deviation": dev}
