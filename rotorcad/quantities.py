"""The unit and short label of every result quantity, declared once: units as data.

Every number a command reports (its JSON key, CONTRACT.md) is declared here beside the module that
computes it: one :class:`Quantity` per key, with its unit and a short label. The command tables,
the HTML report, the sweep's column names and plot axes, and the units that end a points file's
comment take the unit from this table instead of guessing it from the key's name. A key that is not declared shows no unit, and
``tests/test_units_declared.py`` fails: adding a result key means adding one line here.

Units are written as the command tables print them: ``mm``, ``mm²``, ``mm³``, ``mm⁴``, ``deg``,
``m/s``, ``N``, ``N/mm``, ``MPa``, ``bar``, ``rpm``, ``Hz``, ``%``, ``L/min``, ``s``, ``1/s``,
``B`` (bytes), and ``1`` for a pure number (a count, a ratio, a share). :func:`symbol` gives the
form of pictures and of the report (``°``, ``–``), :func:`column_suffix` the ASCII form of CSV
column names (``mm2``, ``m_s``).

Keys are looked up by their dotted path in the JSON (nested objects joined by ``.``, list items
as ``[]``, e.g. ``max_sliding_at.value``), then by its shorter endings down to the key's own name
(``racks.male.hob_tip_radius`` finds ``hob_tip_radius``); a key means the same quantity in every
command that reports it.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from rotorcad.quantities_shop import SHOP_ROWS
from rotorcad.roles import Side

__all__ = ["QUANTITIES", "Quantity", "axis_label", "column_suffix", "csv_units_line", "lookup", "symbol", "unit_of"]


@dataclass(frozen=True)
class Quantity:
    """A result quantity: its JSON key, unit and short label, and the module that computes it.

    Attributes
    ----------
    key : str
        The JSON key, or a dotted path ending in it (``max_sliding_at.value``).
    unit : str
        The unit as the command tables print it; ``"1"`` for a pure number.
    label : str
        A short label for axes and column headings (``"normal clearance"``).
    source : str
        Where it is computed, the module's path without ``.py`` (``rotorcad/clearance``): where to
        look when the number is wrong. A path, not a module name to import: the core names no
        module above it (the architecture test).
    """

    key: str
    unit: str
    label: str
    source: str


QUANTITIES: dict[str, Quantity] = {}
"""Every declared quantity by key (or dotted path)."""


def _declare(source: str, rows: Iterable[tuple[str, str, str]]) -> None:
    """Declare ``(key, unit, label)`` rows computed by module ``source``; a key is declared once."""
    for key, unit, label in rows:
        if key in QUANTITIES and QUANTITIES[key].unit != unit:
            raise ValueError(f"{key} is declared twice with different units ({QUANTITIES[key].unit}, {unit})")
        QUANTITIES.setdefault(key, Quantity(key, unit, label, source))


def _rotors(rows: Iterable[tuple[str, str, str]]) -> list[tuple[str, str, str]]:
    """Each row once per rotor: ``{rotor}_key`` with the label ``{rotor} label``."""
    return [(f"{side}_{key}", unit, f"{side} {label}") for key, unit, label in rows for side in Side]


# --- involute gears (rotorcad/gear.py, rotorcad/cli/gear.py; ISO 21771) ---------------------------
_declare(
    "rotorcad/gears",
    [
        ("pitch_radius", "mm", "pitch radius"),
        ("base_radius", "mm", "base radius"),
        ("tip_radius", "mm", "tip radius"),
        ("root_radius", "mm", "root radius"),
        ("form_radius", "mm", "form radius"),
        ("tooth_thickness_pitch", "mm", "tooth thickness at the pitch circle"),
        ("center_distance", "mm", "centre distance"),
        ("working_pressure_angle_deg", "deg", "working pressure angle"),
        ("contact_ratio", "1", "contact ratio"),
        ("backlash", "mm", "circumferential backlash"),
    ],
)

# --- internal gears and their shaper cutters (rotorcad/gears/internal_gear.py, internal_pair.py,
# shaper.py; ISO 21771, DIN 3993): the cutter's figures nested under cutter (table rows cutter_...)
_declare(
    "rotorcad/gears/internal_gear",
    [
        ("outer_radius", "mm", "outer radius of the ring"),
        ("space_width_pitch", "mm", "space width at the pitch circle"),
        ("cutting_center_distance", "mm", "centre distance of the shaper cutting"),
        ("cutting_pressure_angle_deg", "deg", "working pressure angle of the shaper cutting"),
        ("cutting_involute_margin", "mm", "involute-interference margin of the cutting"),
        ("cutting_trochoid_margin_deg", "deg", "trochoid-interference margin of the cutter"),
        ("cutting_radial_feed_margin_deg", "deg", "radial-feed (trimming) margin of the cutter"),
    ]
    + [
        (f"cutter{sep}{key}", unit, f"shaper cutter {label}")
        for key, unit, label in (
            ("teeth", "1", "teeth"),
            ("shift", "1", "profile shift"),
            ("pitch_radius", "mm", "pitch radius"),
            ("base_radius", "mm", "base radius"),
            ("tip_radius", "mm", "tip radius"),
            ("tip_rounding", "mm", "tip rounding radius"),
        )
        for sep in (".", "_")
    ],
)
_declare(
    "rotorcad/gears/internal_pair",
    [
        ("involute_interference_margin", "mm", "involute-interference margin"),
        ("root_interference_margin", "mm", "pinion tip to the ring's form circle"),
        ("trochoid_margin_deg", "deg", "trochoid-interference margin"),
        ("radial_assembly_margin_deg", "deg", "radial-assembly (trimming) margin"),
        ("min_teeth_difference", "1", "smallest tooth-count difference"),
    ],
)

# --- cutting simulation (hob/, rotorcad/cli/cut_cmd.py) -------------------------------------------
_declare(
    "hob/cutting",
    [
        ("undercut_radius", "mm", "undercut radius"),
        ("undercut_radius_exact", "mm", "undercut radius, exact"),
        ("undercut_radius_model", "mm", "undercut radius, model"),
        ("undercut_radius_model_deviation", "mm", "undercut radius, model less exact"),
        ("max_deviation_from_envelope", "mm", "largest deviation from the envelope"),
        ("flank_deviation_from_envelope", "mm", "flank deviation from the envelope"),
        ("tooth_thickness_pitch_exact", "mm", "tooth thickness at the pitch circle, exact"),
        ("positions", "1", "cutter positions"),
    ],
)

# --- gear pump (rotorcad/pump.py; Kollek) ---------------------------------------------------------
_declare(
    "rotorcad/pump",
    [
        ("mean_flow", "L/min", "mean flow"),
        ("mean_flow_paper", "L/min", "mean flow, paper"),
        ("mean_flow_swept_volume", "L/min", "mean flow, swept volume"),
        ("mean_flow_paper_to_swept_volume", "1", "mean flow, paper to swept volume"),
        ("flow_irregularity", "1", "flow irregularity"),
        ("pump_frequency_hz", "Hz", "pump frequency"),
        ("mate_teeth", "1", "teeth of the mate"),
        ("harmonics[]", "1", "harmonic amplitude (share of the mean flow)"),
        *((f"kollek_series.{k}[]", "1", f"Kollek coefficient, {k.replace('_', ' ')}") for k in ("numerical", "eqs_4_6")),
        ("total_contact_ratio", "1", "total contact ratio"),
        ("trapped_double_contact_deg", "deg", "rotation over which the space is trapped"),
        ("trapped_area_max", "mm²", "largest trapped area"),
        ("trapped_area_min", "mm²", "smallest trapped area"),
        ("trapped_volume_max", "mm³", "largest trapped volume"),
        ("trapped_volume_min", "mm³", "smallest trapped volume"),
        ("trapped_volume_change", "mm³", "trapped volume squeezed out each pitch"),
        ("trapped_flow_max", "L/min", "largest flow out of or into the trapped space"),
    ],
)

# --- Rinder's meshing analysis (rotorcad/meshing.py, rotorcad/blow_hole.py, rotorcad/cli/rotor.py)
_SLIP_POINT = [
    ("x", "mm", "x"),
    ("y", "mm", "y"),
    ("angle_deg", "deg", "male angle"),
    ("male_radius", "mm", "male radius"),
    ("female_radius", "mm", "female radius"),
]
_FLANK = [
    ("meshline_length", "mm", "meshline length"),
    ("working_length", "mm", "working length of the meshline"),
    ("geometric_share", "1", "geometric share of the meshline"),
    ("transverse_contact_ratio", "1", "transverse contact ratio"),
    ("overlap_contact_ratio", "1", "overlap contact ratio"),
    ("total_contact_ratio", "1", "total contact ratio"),
    ("transverse_contact_ratio_accuracy", "1", "accuracy of the transverse contact ratio"),
]
_declare(
    "rotorcad/meshing",
    [
        ("male_teeth", "1", "male teeth"),
        ("female_teeth", "1", "female teeth"),
        ("blow_hole_area", "mm²", "blow-hole area"),
        ("blow_hole_uncertainty", "mm²", "blow-hole area uncertainty from the input's accuracy"),
        ("contact_line_length", "mm", "contact line length"),
        ("male_flute_area", "mm²", "male flute area"),
        ("female_flute_area", "mm²", "female flute area"),
        ("displacement_per_rev", "mm³", "displacement per male revolution"),
        ("area_utilisation", "1", "area utilisation"),
        ("max_sliding_velocity", "m/s", "largest sliding velocity"),
        ("max_sliding_at.value", "m/s", "largest sliding velocity"),
        ("max_slip_male.value", "1", "largest male slip"),
        ("max_slip_female.value", "1", "largest female slip"),
        *(
            (f"{point}.{key}", unit, label)
            for point in ("max_sliding_at", "max_slip_male", "max_slip_female", "slip_singularities[]")
            for key, unit, label in _SLIP_POINT
        ),
        ("speed_rpm", "rpm", "male speed"),
        ("defects[].x", "mm", "x"),
        ("defects[].y", "mm", "y"),
        ("defects[].angle_deg", "deg", "male angle"),
        ("defects[].extent", "mm", "extent along the profile"),
        ("defects[].margin", "mm", "profile radius about the corner generating its path"),
        ("defects[].margin_accuracy", "mm", "point spacing within which a tip corner is undecided"),
        ("defects[].corner[]", "mm", "tip corner in the rotor's own frame"),
        ("undecided_defects[].x", "mm", "x"),
        ("undecided_defects[].y", "mm", "y"),
        ("undecided_defects[].extent", "mm", "meshline within a point spacing of the corner"),
        ("undecided_defects[].margin", "mm", "profile radius about the corner generating its path"),
        ("undecided_defects[].margin_accuracy", "mm", "point spacing within which a tip corner is undecided"),
        ("undecided_defects[].corner[]", "mm", "tip corner in the rotor's own frame"),
        ("defect_accuracy", "mm", "accuracy of the defect search"),
        ("defect_resolution", "mm", "shortest meshline stretch the defect search resolves"),
        *((f"flanks.{flank}.{key}", unit, label) for flank in ("driving", "sealing") for key, unit, label in _FLANK),
        ("overlap_contact_ratio", "1", "overlap contact ratio"),
        ("wrap_angle_deg", "deg", "wrap angle"),
        ("rack_loss_percent", "%", "rack loss"),
    ],
)
_declare(
    "rotorcad/blow_hole",
    [
        ("blow_hole_spatial.area", "mm²", "spatial blow-hole area"),
        ("blow_hole_spatial.projected_area", "mm²", "projected blow-hole area"),
        ("blow_hole_spatial.apex[]", "mm", "apex coordinate"),
        ("blow_hole_spatial.z_min", "mm", "lowest z"),
        ("blow_hole_spatial.z_max", "mm", "highest z"),
        ("blow_hole_spatial.male_tip_meets_cusp_z", "mm", "z where the male tip meets the housing cusp"),
        ("blow_hole_spatial.female_tip_meets_cusp_z", "mm", "z where the female tip meets the housing cusp"),
    ],
)

# --- hobbability (hob/verdict.py, hob/rack.py) -----------------------------------------------------
_declare(
    "hob/verdict",
    [
        ("rack_deviation", "mm", "rack deviation"),
        ("normal_pressure_angle_min_deg", "deg", "smallest normal pressure angle"),
        ("smallest_flank_angle_accuracy_deg", "deg", "accuracy of the smallest flank angle read from points"),
        ("undercut_accuracy", "mm", "depth below which a mate's turned-back envelope is no undercut"),
        ("rack_accuracy", "mm", "how far the rack from a rotor's points may lie from its true rack"),
        ("undercut_limit_shift", "1", "profile shift from which the gear is not undercut"),
        ("hob_tip_radius", "mm", "hob tip radius"),
        ("hob_root_radius", "mm", "hob root radius"),
        ("hob_tip_thickness", "mm", "hob tip thickness"),
        ("helix_angle_deg", "deg", "helix angle"),
        ("no_rack_share", "1", "share without a rack"),
    ],
)

# --- the hob's basic worm (hob/worm.py, rotorcad/cli/hob_worm.py; DIN 3968 / ISO 1122-1 terms) ---------
_declare(
    "hob/worm",
    [
        ("starts", "1", "thread starts"),
        ("outside_diameter", "mm", "hob outside diameter"),
        ("reference_diameter", "mm", "hob reference diameter"),
        ("root_diameter", "mm", "hob root diameter"),
        ("thread_depth", "mm", "thread depth"),
        ("normal_pitch", "mm", "normal pitch"),
        ("axial_pitch", "mm", "axial pitch"),
        ("lead", "mm", "lead"),
        ("lead_angle_deg", "deg", "lead angle"),
        ("worm_length", "mm", "worm length"),
        ("gash_count", "1", "gashes"),
        ("gash_depth", "mm", "gash depth"),
        ("rack_join_max", "mm", "largest rack gap bridged"),
        ("face_count", "1", "STEP faces"),
        ("step_deviation", "mm", "STEP faces from the helicoid"),
    ],
)

# --- interference (rotorcad/interference.py, rotorcad/cli/interfere_cmd.py) -----------------------
_declare(
    "rotorcad/interference",
    [
        ("phase_deg", "deg", "female phase"),
        ("max_intersection_volume", "mm³", "largest intersection volume"),
        ("max_intersection_volume_raw", "mm³", "largest intersection volume, raw"),
        ("angle_deg", "deg", "male angle"),
        ("housing_intersection_volume", "mm³", "intersection volume with the housing"),
        ("steps", "1", "angle steps"),
        ("touching_threshold", "mm³", "touching threshold"),
        ("max_penetration", "mm", "largest penetration"),
    ],
)

# --- meshing clearance from points (rotorcad/clearance.py; Wu & Chi) ------------------------------
_declare(
    "rotorcad/clearance",
    [
        ("max_normal_clearance", "mm", "largest normal clearance"),
        ("min_normal_clearance", "mm", "smallest normal clearance"),
        ("mean_clearance", "mm", "mean normal clearance"),
        ("equal_clearance", "mm", "equal clearance (band area / contact line length)"),
        ("band_area", "mm²", "clearance band area"),
        ("wetted_perimeter", "mm", "wetted perimeter"),
        ("max_gap", "mm", "largest transverse gap"),
        ("min_gap", "mm", "smallest transverse gap"),
        ("min_corner_gap", "mm", "smallest gap of a sharp female corner"),
        ("contact_zone_share", "1", "contact zone share"),
        ("max_unresolved_clearance", "mm", "largest normal clearance the points cannot resolve"),
        ("min_unresolved_clearance", "mm", "smallest normal clearance the points cannot resolve"),
        ("unresolved_share", "1", "unresolved share"),
        ("driving_min_normal_clearance", "mm", "smallest normal clearance, driving flank"),
        ("driving_max_normal_clearance", "mm", "largest normal clearance, driving flank"),
        ("driving_mean_clearance", "mm", "mean normal clearance, driving flank"),
        ("sealing_min_normal_clearance", "mm", "smallest normal clearance, sealing flank"),
        ("sealing_max_normal_clearance", "mm", "largest normal clearance, sealing flank"),
        ("sealing_mean_clearance", "mm", "mean normal clearance, sealing flank"),
        ("lands_min_normal_clearance", "mm", "smallest normal clearance, lands"),
        ("lands_max_normal_clearance", "mm", "largest normal clearance, lands"),
        ("lands_mean_clearance", "mm", "mean normal clearance, lands"),
        ("accuracy", "mm", "accuracy of the points"),
        ("gap_accuracy", "mm", "accuracy of the gaps and corner gap"),
        ("female_rack_shift", "mm", "female rack shift"),
    ],
)
_declare(  # the hot pair, with --suction/--discharge-temperature (rotorcad/clearance_thermal.py; Miao et al. sec. 1.2)
    "rotorcad/clearance_thermal",
    [
        ("rotor_temperature", "degC", "rotor temperature (mean of suction and discharge)"),
        ("housing_temperature", "degC", "housing temperature"),
        ("reference_temperature", "degC", "temperature of the points"),
        ("rotor_expansion", "1/K", "rotors' expansion coefficient"),
        ("housing_expansion", "1/K", "housing's expansion coefficient"),
        ("center_distance_cold", "mm", "centre distance at the reference temperature"),
    ],
)
CLEARANCE_CSV_COLUMNS: dict[str, str] = {
    "x": "mm",
    "y": "mm",
    "clearance": "mm",
    "male_angle_deg": "deg",
    "z": "mm",
    "contact_x": "mm",
    "contact_y": "mm",
    "female_x": "mm",
    "female_y": "mm",
    "male_x": "mm",
    "male_y": "mm",
    "in_contact": "1",
    "zone": "1",
    "gap": "mm",
    "flank": "1",
}
"""Units of the columns of ``rotorcad clearance --csv`` (rotorcad.clearance.MeshingClearance.distribution)."""

POINTS_CSV_COLUMNS: dict[str, str] = {"x": "mm", "y": "mm"}
"""Units of the columns of a points file (CONTRACT.md, "Points files")."""

INDICATOR_CSV_COLUMNS: dict[str, str] = {"angle_deg": "deg", "pressure_bar": "bar"}
"""Units of the columns of an indicator diagram (``rotorcad deflect --indicator``)."""

# --- deflection under gas load (rotorcad/deflection.py; Rinder & Deix) ----------------------------
_declare(
    "rotorcad/deflection",
    [
        *_rotors(
            [
                ("max_deflection", "mm", "largest deflection"),
                ("max_deflection_position", "mm", "position of the largest deflection"),
                ("deflection_direction_deg", "deg", "direction of the largest deflection"),
                ("max_deflection_helical", "mm", "largest deflection of the helical part"),
                ("max_deflection_helical_ritz2", "mm", "largest deflection of the helical part, 2 terms"),
                ("equivalent_diameter", "mm", "equivalent diameter"),
                ("root_diameter", "mm", "root diameter"),
                ("section_area", "mm²", "section area"),
                ("second_moment", "mm⁴", "second moment of area"),
                ("second_moment_core", "mm⁴", "second moment of area of the core"),
                ("second_moment_reduced", "mm⁴", "reduced second moment of area"),
                ("kappa_min", "1", "smallest ratio kappa"),
                ("kappa_max", "1", "largest ratio kappa"),
                ("worst_angle_deg", "deg", "worst male angle"),
                ("gas_force_n", "N", "gas force"),
                ("gas_force_direction_deg", "deg", "direction of the gas force"),
                ("discharge_bearing_load_n", "N", "discharge bearing load"),
                ("discharge_bearing_load_max_n", "N", "largest discharge bearing load"),
                ("suction_bearing_load_n", "N", "suction bearing load"),
                ("suction_bearing_load_max_n", "N", "largest suction bearing load"),
            ]
        ),
        *_rotors(
            [
                ("body_deflection", "mm", "largest deflection of the rotor body in its bore"),
                ("deflection_to_housing_clearance", "1", "body deflection to radial housing clearance"),
            ]
        ),
        ("housing_radial_clearance", "mm", "radial clearance of the housing"),
        ("angle_eq10_deg", "deg", "worst male angle by eq. (10)"),
        ("suction_closing_deg", "deg", "suction closes"),
        ("discharge_opening_deg", "deg", "discharge opens"),
        ("volume_ratio", "1", "built-in volume ratio"),
        ("chamber_max_volume", "mm³", "largest chamber volume"),
        ("displacement_per_male_rev", "mm³", "displacement per male revolution"),
        ("chambers[].chamber_angle_deg", "deg", "chamber angle"),
        ("chambers[].pressure_bar", "bar", "chamber pressure"),
        ("chambers[].from_z", "mm", "chamber from z"),
        ("chambers[].to_z", "mm", "chamber to z"),
        ("terms", "1", "sine terms"),
        # the two flute loads side by side, and the paper's value over rotorcad's
        *(
            row
            for name in ("rotorcad", "paper")
            for row in [
                *_rotors(
                    [
                        (f"max_deflection_helical_{name}", "mm", f"largest deflection of the helical part, {name} load"),
                        (f"max_deflection_{name}", "mm", f"largest deflection, {name} load"),
                        (f"gas_force_n_{name}", "N", f"gas force, {name} load"),
                    ]
                ),
                (f"angle_deg_{name}", "deg", f"male angle, {name} load"),
            ]
        ),
        *_rotors(
            [
                ("max_deflection_helical_paper_to_rotorcad", "1", "largest deflection of the helical part, paper to rotorcad"),
                ("max_deflection_paper_to_rotorcad", "1", "largest deflection, paper to rotorcad"),
                ("gas_force_n_paper_to_rotorcad", "1", "gas force, paper to rotorcad"),
            ]
        ),
    ],
)

# --- gear coupling oil film (rotorcad/coupling.py, rotorcad/coupling_film.py; Belkov et al.) -----
_declare(
    "rotorcad/coupling",
    [
        ("min_film_thickness", "mm", "smallest film thickness"),
        ("load_capacity", "N", "load capacity of the film"),
        ("max_pressure", "MPa", "largest film pressure"),
        ("hertz_stress", "MPa", "Hertz stress"),
        ("central_film_thickness", "mm", "central film thickness"),
        ("ehl_film_thickness", "mm", "EHL film thickness"),
        ("ehl_ratio", "1", "film thickness to EHL"),
        ("pressure_to_hertz_ratio", "1", "film pressure to Hertz stress"),
        ("tooth_load", "N", "tooth load"),
        ("load_per_length", "N/mm", "load per contact length"),
        ("barrel_radius", "mm", "barrel radius"),
        ("flank_crown_radius", "mm", "flank crown radius"),
        ("crowning_depth", "mm", "crowning depth"),
        ("contact_length", "mm", "contact length"),
        ("hertz_half_width", "mm", "Hertz half width"),
        ("contact_excursion", "mm", "contact excursion"),
        ("inlet_length", "mm", "inlet length"),
        ("inlet_room", "mm", "inlet room"),
        ("mean_sliding_velocity", "m/s", "mean sliding velocity"),
        ("mean_entraining_velocity", "m/s", "mean entraining velocity"),
        ("max_rolling_velocity", "m/s", "largest rolling velocity"),
        ("max_axial_sliding_velocity", "m/s", "largest axial sliding velocity"),
        ("film_parameter", "1", "film parameter"),
        ("roughness", "mm", "combined roughness"),
        ("eq7_velocity", "m/s", "velocity of eq. (7)"),
        ("min_film_thickness_rotorcad", "mm", "smallest film thickness, rotorcad"),
        ("min_film_thickness_paper", "mm", "smallest film thickness, paper"),
        ("min_film_thickness_paper_to_rotorcad", "1", "smallest film thickness, paper to rotorcad"),
        ("ehl_film_thickness_rotorcad", "mm", "EHL film thickness, rotorcad"),
        ("ehl_film_thickness_paper", "mm", "EHL film thickness, paper"),
        ("ehl_film_thickness_paper_to_rotorcad", "1", "EHL film thickness, paper to rotorcad"),
    ],
)

# --- solids in files (exports/, rotorcad/cli/export_cmd.py) --------------------------------------
_declare(
    "rotorcad/cli/export_cmd",
    [
        ("files[].triangles", "1", "triangles"),
        ("files[].volume", "mm³", "volume of the body"),
        ("files[].tolerance", "mm", "surface tolerance"),
        ("files[].size", "B", "file size"),
        ("files[].spline_deviation", "mm", "largest distance of the drawing's splines from the exact outline"),
        ("tolerance", "mm", "surface tolerance"),
        ("clearance", "mm", "radial clearance of the housing"),
    ],
)

# --- design sweeps (rotorcad/sweep/; the summary of rotorcad/cli/sweep_cmd.py) ---------------------
_declare(
    "rotorcad/cli/sweep_cmd",
    [
        ("variants", "1", "variants"),
        ("computed", "1", "variants computed"),
        ("resumed", "1", "variants resumed"),
        ("failed", "1", "variants failed"),
        ("seconds", "s", "wall time"),
        ("variants_per_second", "1/s", "variants per second"),
        ("cpu_seconds", "s", "CPU time"),
        ("feasible", "1", "feasible variants"),
        ("pareto_front", "1", "variants on the Pareto front"),
        ("rank", "1", "rank"),
        ("variant", "1", "variant"),
    ],
)

# the columns of a sweep's table (rotorcad/sweep/tasks.py; CONTRACT.md, sweep rows): the unit ends the name
SWEEP_COLUMNS: dict[str, Quantity] = {
    key: Quantity(key, unit, label, "rotorcad/sweep/tasks")
    for key, unit, label in [
        ("blow_hole_area_mm2", "mm²", "blow-hole area"),
        ("contact_line_length_mm", "mm", "contact line length"),
        ("male_flute_area_mm2", "mm²", "male flute area"),
        ("female_flute_area_mm2", "mm²", "female flute area"),
        ("displacement_per_rev_mm3", "mm³", "displacement per male revolution"),
        ("area_utilisation", "1", "area utilisation"),
        ("max_sliding_velocity_m_s", "m/s", "largest sliding velocity"),
        ("max_slip_male", "1", "largest slip, male"),
        ("max_slip_female", "1", "largest slip, female"),
        ("wrap_angle_deg", "deg", "wrap angle"),
        ("rack_loss_percent", "%", "rack loss"),
        ("defects", "1", "meshline defects"),
        ("defects_cusp", "1", "cusps on the meshline"),
        ("defects_jamming", "1", "jamming points on the meshline"),
        ("defects_slipping", "1", "slipping points on the meshline"),
        ("interference_volume_mm3", "mm³", "largest intersection volume of the pair"),
        ("housing_intersection_volume_mm3", "mm³", "volume of the rotors outside the bores"),
        ("male_volume_mm3", "mm³", "male volume"),
        ("female_volume_mm3", "mm³", "female volume"),
        ("clearance_mean_mm", "mm", "mean normal clearance"),
        ("clearance_max_mm", "mm", "largest normal clearance"),
        ("clearance_min_mm", "mm", "smallest normal clearance"),
        ("clearance_band_area_mm2", "mm²", "clearance band area"),
        ("seconds", "s", "time per variant"),
        ("rank", "1", "rank"),
    ]
}
"""Every numeric column of a sweep's table (Parquet, CSV) with its unit and plot label."""

# --- a section's end face and its fit to the design (rotorcad/measured/end_face.py) ------------------
_declare(
    "rotorcad/measured/end_face",
    [
        ("design_deviation.as_read", "mm", "RMS distance from the design's outline"),
        ("design_deviation.mirrored", "mm", "mirror image's RMS distance from the design's outline"),
    ],
)

# --- the report page (rotorcad/cli/report_cmd.py) -------------------------------------------------
_declare("rotorcad/cli/report_cmd", [("defect_count", "1", "defects")])

# --- design-file inputs shown beside the results (rotorcad/design.py; the report's design table) ---
_declare(
    "rotorcad/design",
    [
        ("lead", "mm", "male lead"),
        ("length", "mm", "rotor length"),
        ("male_tip_radius", "mm", "male tip radius"),
        ("male_root_radius", "mm", "male root radius"),
        ("female_tip_radius", "mm", "female tip radius"),
        ("female_root_radius", "mm", "female root radius"),
        ("radial_clearance", "mm", "radial clearance of the housing"),
        ("suction_pressure_bar", "bar", "suction pressure (absolute)"),
        ("discharge_pressure_bar", "bar", "discharge pressure (absolute)"),
        ("polytropic_exponent", "1", "polytropic exponent"),
        ("discharge_edge_deg", "deg", "discharge control edge"),
        ("young_modulus", "N/mm²", "Young's modulus"),
        ("poisson_ratio", "1", "Poisson's ratio"),
        ("teeth", "1", "teeth"),
        ("module", "mm", "module"),
        ("pressure_angle_deg", "deg", "pressure angle"),
        ("face_width", "mm", "face width"),
    ],
)

# --- the clearance designed into the female by rotor --clearance (rotorcad/clearance_design.py) ----
_declare(
    "rotorcad/clearance_design",
    [
        ("designed_clearance.driving", "mm", "designed clearance, driving flank"),
        ("designed_clearance.sealing", "mm", "designed clearance, sealing flank"),
        ("designed_clearance.lands", "mm", "designed clearance, lands"),
        ("designed_clearance.blend", "mm", "length of the blend between flank clearances"),
    ],
)


def csv_units_line(columns: Iterable[str]) -> str | None:
    """Return the words naming each CSV column's unit, ``units: x mm, y mm`` (None if one is not declared).

    :func:`exports.csv_points.write_points` ends the file's last comment line with them; readers
    skip comments, so files without them (written before) read the same.

    Parameters
    ----------
    columns : iterable of str
        The column names of the header line.

    Returns
    -------
    str or None
    """
    table = POINTS_CSV_COLUMNS | CLEARANCE_CSV_COLUMNS | INDICATOR_CSV_COLUMNS
    names = list(columns)
    if not names or any(name not in table for name in names):
        return None
    return "units: " + ", ".join(f"{name} {table[name]}" for name in names)


def lookup(key: str) -> Quantity | None:
    """Return the declaration of a key or dotted path, or None if it has none.

    The whole path first, then its shorter endings (``a.b.c``, ``b.c``, ``c``); list items may be
    written ``[]`` or with their index (``chambers.0.pressure_bar``).

    Parameters
    ----------
    key : str
        A JSON key or dotted path.

    Returns
    -------
    Quantity or None
    """
    parts = [p for p in key.replace("[]", ".[]").split(".") if p]
    parts = ["[]" if p.isdigit() else p for p in parts]
    for start in range(len(parts)):
        name = ".".join(parts[start:]).replace(".[]", "[]")
        if name.startswith("[]"):
            continue
        if name in QUANTITIES:
            return QUANTITIES[name]
    return None


def unit_of(key: str) -> str:
    """Return the unit of a result key as the command tables print it ("" if not declared).

    Parameters
    ----------
    key : str
        A JSON key or dotted path, e.g. ``max_normal_clearance``.

    Returns
    -------
    str
        ``mm``, ``mm²``, ``deg``, ... ; ``"1"`` for a pure number.
    """
    q = lookup(key)
    return q.unit if q is not None else ""


_SYMBOLS = {"deg": "°", "degC": "°C", "1": "–", "": "–"}
_ASCII = {
    "mm²": "mm2",
    "mm³": "mm3",
    "mm⁴": "mm4",
    "m/s": "m_s",
    "N/mm": "N_mm",
    "L/min": "L_min",
    "1/s": "per_s",
    "%": "percent",
}


def symbol(unit: str) -> str:
    """Return a unit as pictures and the report show it: ``°`` for degrees, ``–`` for a pure number."""
    return _SYMBOLS.get(unit, unit)


def axis_label(key: str, label: str | None = None) -> str:
    """Return an axis label ``label [unit]`` for a declared key (rotorcad.plot_style conventions).

    Parameters
    ----------
    key : str
        The quantity's key.
    label : str, optional
        A label to use instead of the declared one.

    Returns
    -------
    str
    """
    q = lookup(key)
    if q is None:
        raise KeyError(f"{key} has no declaration in rotorcad.quantities")
    return f"{label or q.label} [{symbol(q.unit)}]"


def column_suffix(unit: str) -> str:
    """Return a unit in the ASCII form of CSV and Parquet column names (``mm2``, ``m_s``; "" for a pure number)."""
    if unit in ("1", ""):
        return ""
    return _ASCII.get(unit, unit)


# --- the shop: form grinding, the gear as a part and as the shop makes and checks it, inspection
# (rotorcad/grinding/, rotorcad/gears/, rotorcad/inspection/; their rows in rotorcad/quantities_shop.py)
for _source, _rows in SHOP_ROWS:
    _declare(_source, _rows)
