"""Meshing analysis of a screw-rotor pair after Rinder (*Sonderverzahnungen für Schraubenverdichterrotoren*).

Meshline, contact line (eq. 1), the kinematic rules of sec. 2.2.1 (cusp, jamming, slipping),
tightness and blow-hole (sec. 2.2.2), flute areas and displacement, sliding velocity and slip
(eqs. 2-4).

The package, one job a module (every name importable from ``rotorcad.meshing`` as before):
:mod:`~rotorcad.meshing.meshline` (the meshline's pieces, their sampling, tangents, turns and
corners), :mod:`~rotorcad.meshing.defect_record` (a defect and the resolution it is judged to),
:mod:`~rotorcad.meshing.defects` (the rules of sec. 2.2.1 judged to the profile's accuracy),
:mod:`~rotorcad.meshing.slipping` (the slipping rule between the meshline's pieces),
:mod:`~rotorcad.meshing.rotation_turns` (jamming from the male rotation turning back along a given meshline),
:mod:`~rotorcad.meshing.contact_ratios` (working part, contact ratios, running per flank),
:mod:`~rotorcad.meshing.angles` (the one angle convention), :mod:`~rotorcad.meshing.apex` (the
blow-hole's apex of a given profile from the closed-form meshline of a fitted arc),
:mod:`~rotorcad.meshing.slip` (slip and the points of infinite slip, eq. 4) and
:mod:`~rotorcad.meshing.analysis` (:class:`MeshingAnalysis`: the verdict and the summary).

The meshline is the set of contact points in the fixed transverse frame: for a rack-generated
pair the rack touches both rotors at the same point, so it is the rack's contact locus. Only
contacts inside both bores (tip circles) count. Its tangent comes from an interpolating spline of
each piece over the generating parameter (never from point differences).

Rinder's criteria, as this module applies them
----------------------------------------------
*Geometric contact* (sec. 1.2, of Krigar's profile: "Eine Berührung der Flanken ... im
geometrischen Sinn mit gemeinsamen Tangenten im Eingriffspunkt, wie sie für eine lauffähige
Verzahnung gefordert werden muß"): the two flanks touch with a common tangent. A rack curve
touching both rotors gives it; the path of a tip corner (a *point-generated* flank part, "Radlinien
der Punkte P_H und P_N") does not: it is a corner against a flank.

*Working part* of a flank: its meshline with geometric contact. Point-generated parts seal (they
carry the meshline to the housing cusp, sec. 2.2.2) but do not drive; Rinder's narrow-tip profile
has "lange, punkterzeugte Flankenteile an der Dichtflanke" and still "gute Laufeigenschaften an
beiden Flankenteilen", and the asymmetric SRM profile's sealing flank runs properly "zumindest in
einem kleinen Flankenbereich" (a short straight female flank): a working part of any length makes
the flank run, with the helix.

*Cusp* (Spitze, sec. 2.2.1): a meshline point whose normal passes through O1 (a cusp on the male
flank) or O2 (on the female). Rinder names these in the profiles he calls runnable ("vgl. Bild 1,
2, 3 und 4") and says of the tips "Am Haupt- bzw. Nebenläuferkopf ist demnach nur eine Spitze oder
Ecke als Flanke denkbar" (sec. 2.2.2). So a cusp that is a rotor's tip corner is no defect: a
point-generated piece (the corner's path, its normal through the centre all along) and a cusp on
either tip circle, where the working flank hands over to a tip corner's path (a smooth flank touches
its tip circle only on O1O2), end the working part (:func:`is_tip_corner`; the JSON says
``tip_corner``). A corner's path that runs across O1O2 (Krigar's male tip corner) is the corner of
both flanks: its lobe part is the tip (the root below C), not the side its middle falls on. A cusp
inside a working part, off the tip circles, is a defect: the flank reverses (an undercut). The
rack-involute pair shows it: its female sealing involute is used down to its base circle, where its
cusp meets the male tip corner.

*Jamming* (Klemmen): the meshline normal passes through the pitch point C, except where "beide
Flankenkrümmungsmittelpunkte mit dem Wälzpunkt zusammenfallen" (Lysholm's circular driving flank and
the symmetric SRM flanks, circles about C: their meshline is an arc about C). Such an arc is known
from its normals or from its positions alone (:func:`~rotorcad.meshing.defects.arcs_about`: every
stretch of twice the resolution keeps its distance from C within the meshline's accuracy), since a
tangent fitted through a given profile's meshline wobbles along it. Away from O1O2 the normal passes
through C exactly where the male rotation turns back along the meshline (d|P - C|/dt = c P_y / |P - C|);
a given profile's jamming is also read so, where the rotation turns back by more than the accuracy of
its normal allows (:mod:`~rotorcad.meshing.rotation_turns`: a dent finer than the resolution, whose
normal's sign changes cancel within it).

*Slipping* (Durchrutschen): the meshline crosses O1O2 away from C; no flank drives the other there,
but "durch die verschraubten Zähne stellt diese Bedingung aber keine Einschränkung ... dar": it
does not count against running.

*Contact ratios* per flank (helical-gear sense): the transverse ratio is the male rotation over
which the working part is in contact, per angular pitch 2 pi / z1 (0 for a circle about C, which
touches at one instant: Lysholm's "nur infinitesimale Stirnüberdeckung"); the overlap ratio
(Sprungüberdeckung) is the male rotation over which one lobe's contact line lasts along the rotor,
the wrap angle 2 pi L / h1, per angular pitch: z1 L / h1; the total ratio is their sum. The helix
carries only a working contact along the rotor, so a flank without a working part has overlap 0.

*Runs* (a flank runs, i.e. carries the drive in the sense of rotation that loads it): it has a
working part, no cusp or jamming inside it, and a total contact ratio of at least 1 ("Die nur
infinitesimale Stirnüberdeckung wird durch ... hohe Sprungüberdeckung kompensiert"; the symmetric
SRM profile runs "bei ausreichender Verschraubung der Zähne in beiden Drehrichtungen").
*Runs without timing gears*: both flanks run (Rinder: "Lauffähigkeit in beiden Drehrichtungen",
sec. 2.1); Lysholm's profile, whose sealing flank has no working part, needs them ("ohne
Koppelgetriebe nicht einwandfrei verwendbar").

Judged to the input's accuracy
------------------------------
A profile given by points or a drawing carries an accuracy e (:attr:`MeshingAnalysis.judged_accuracy`,
reported as ``defect_accuracy``); a feature smaller than it is no verdict. A sign change of a normal's
miss counts only beyond its band and when it persists over the resolution sqrt(8 a e)
(:func:`resolution`); the normals of a meshline generated from scattered points are judged to
:data:`MESHLINE_GAIN` times e (the normal's error moves the contact along the meshline), their tangent the
direction of its smoothing cubic's chord over that resolution (:func:`~rotorcad.meshing.meshline.resolved_tangents`:
the fit between points errs in waves two spacings long, which the meshline magnifies); no sign change is
placed in a gap of a piece's meshline longer than the resolution (contacts outside a bore, left out) nor where
the tangent's chord reaches into one (:func:`~rotorcad.meshing.defects.meshline_gaps`); a working
part shorter than the resolution is none, and so is a curve contact between the male tip corner's
path and the female's shorter than the meshline's resolution sqrt(8 a G e) (G = :data:`MESHLINE_GAIN`):
the fit's rounding of a corner-to-corner hand-over (:func:`~rotorcad.meshing.contact_ratios.is_corner_handover`).
A flank whose working part holds no step the input resolves as working (every contact within the meshline's
accuracy of a tip corner, or within the resolution of one all along) is *undecided at this accuracy*: not
shown to run, and ``running_decided`` is false (:attr:`~rotorcad.meshing.contact_ratios.FlankReport.running_decided`).
So is a flank that would run but where the male rotation turns back and on again by more than the tangent's
tolerance alone allows (the design's test would read jamming) and by less than the input's accuracy does: a
jamming it can neither show nor rule out, named in ``undecided_defects`` (:func:`~rotorcad.meshing.undecided.possible_rows`).
A point of infinite slip (a rotor's v_t = 0, where the meshline crosses the circle on that rotor's
centre and C as diameter) on a tip corner's path that runs on its pitch circle within the meshline's
accuracy is C's rolling, and one at a corner of the meshline that the fit rounds is judged at the
corner (:func:`~rotorcad.meshing.slip.slip_singularities`). The blow-hole carries the
uncertainty the input leaves it, and where that exceeds half the area (and 0.1 % of the female flute's,
:data:`~rotorcad.meshing.blow_hole_accuracy.BLOW_HOLE_RESOLUTION`) the input does not resolve it
(:attr:`MeshingAnalysis.blow_hole_resolved`). A cusp of the design survives: a given profile's corner
path on a rotor's tip circle is that tip corner's point-generated flank by construction (found from
positions in :mod:`rotorcad.measured.pairs`, not from the noisy tangent). Points whose scatter would
put the resolution over a quarter of the lobe's depth are refused (:func:`largest_scatter`).

Angle convention
----------------
Every angle a user reads (JSON ``angle_deg`` keys, tables, pictures, report, README) is
:meth:`MeshingAnalysis.rinder_angle`: the male rotation still to go until the middle of a male tip
reaches the line of centres O1O2 (the lobe pointing at O2), positive before and negative after that
instant. In it the male tip reaches the housing cusp on the sealing side at a negative angle, as in
Rinder's Figs. 10-13 ("ca. -25°", sec. 3.2). The figures themselves are not legible in the source;
this zero and sign are read from the text of sec. 3.2.

Blow-hole (projected definition, stated because the paper gives no formula): the curvilinear
triangle in the transverse plane between the meshline's end E nearest the housing cusp K and K
itself, bounded by the arc of the female tip circle from K to the radial projection of E on it, the
arc of the male tip circle from K to the radial projection of E on it, and the two radial pieces
to E. It is zero when the meshline runs into the cusp. The spatial (curvilinear) blow-hole is
:class:`rotorcad.blow_hole.SpatialBlowHole` (:attr:`MeshingAnalysis.spatial_blow_hole`).
"""

from rotorcad.meshing.analysis import MeshingAnalysis
from rotorcad.meshing.angles import ANGLE_CONVENTION, tip_on_centre_line
from rotorcad.meshing.apex import arc_at, circle_bounds, circle_meshline_apex, fit_circle
from rotorcad.meshing.blow_hole_accuracy import BLOW_HOLE_RESOLUTION
from rotorcad.meshing.contact_ratios import FlankReport, flank_reports, handover_length, is_corner_handover, running_reasons
from rotorcad.meshing.defects import (
    MESHLINE_GAIN,
    VERDICT_SHARE,
    Defect,
    arcs_about,
    is_tip_corner,
    largest_scatter,
    meshline_defects,
    resolution,
    robust_zeros,
    slipping_between_pieces,
)
from rotorcad.meshing.meshline import (
    SHARP_TURN,
    UNEVEN,
    MeshlinePiece,
    even_meshline_parameters,
    flank_roles,
    meshline_tangents,
    reversals,
    turn_corner,
    with_neighbours,
)
from rotorcad.meshing.slip import SLIP_ZERO, on_pitch_circle, slip_singularities, tangential_lever

__all__ = [
    "ANGLE_CONVENTION",
    "BLOW_HOLE_RESOLUTION",
    "MESHLINE_GAIN",
    "SHARP_TURN",
    "SLIP_ZERO",
    "UNEVEN",
    "VERDICT_SHARE",
    "Defect",
    "FlankReport",
    "MeshingAnalysis",
    "MeshlinePiece",
    "arc_at",
    "arcs_about",
    "circle_bounds",
    "circle_meshline_apex",
    "even_meshline_parameters",
    "fit_circle",
    "flank_reports",
    "flank_roles",
    "handover_length",
    "is_corner_handover",
    "is_tip_corner",
    "largest_scatter",
    "meshline_defects",
    "meshline_tangents",
    "on_pitch_circle",
    "resolution",
    "reversals",
    "robust_zeros",
    "running_reasons",
    "slip_singularities",
    "slipping_between_pieces",
    "tangential_lever",
    "tip_on_centre_line",
    "turn_corner",
    "with_neighbours",
]
