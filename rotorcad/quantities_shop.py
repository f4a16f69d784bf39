"""The units of the shop's results: form grinding, the gear as a part and as the shop makes and checks it, inspection.

Rows ``(key, unit, label)`` by the module that computes them, as data: :mod:`rotorcad.quantities` declares
each (its module docstring says how keys are looked up). Kept apart so that each table stays short.
"""

from __future__ import annotations

__all__ = ["SHOP_ROWS"]

# a gear as the shop makes and checks it (DIN 3967 / ISO 21771): nested figures by their path and by the
# row name of the table
_SHOP = [
    ("thickness_allowance", ("upper", "lower"), "mm", "tooth-thickness allowance"),
    ("span", ("nominal", "upper", "lower"), "mm", "span W_k"),
    ("over_pins", ("nominal", "upper", "lower"), "mm", "dimension over pins or balls M_d"),
    ("backlash_circumferential", ("nominal", "max", "min"), "mm", "circumferential backlash"),
    ("backlash_normal", ("nominal", "max", "min"), "mm", "normal backlash"),
]

SHOP_ROWS: list[tuple[str, list[tuple[str, str, str]]]] = [
    # --- form grinding (rotorcad/grinding/, rotorcad/cli/grind_cmd.py; the wheel from the rotor) -------
    (
        "rotorcad/grinding",
        [
            ("lobe_count", "1", "lobes"),
            ("setting_radius", "mm", "radius of the crossing angle's helix"),
            ("crossing_angle_deg", "deg", "crossing angle"),
            ("flute_turn_deg", "deg", "flute turn to the wheel"),
            ("wheel_radius", "mm", "wheel outside radius"),
            ("profile_point_count", "1", "wheel profile points"),
            ("profile_axial_length", "mm", "wheel profile axial length"),
            ("profile_radial_length", "mm", "wheel profile radial length"),
            ("wheel_max_radius", "mm", "wheel largest radius"),
            ("wheel_min_radius", "mm", "wheel least radius"),
            ("profile_folds", "1", "folds of the wheel profile"),
            ("no_contact_point_count", "1", "points without contact"),
            ("unreached_point_count", "1", "points not ground"),
            ("secondary_cutting_point_count", "1", "points cut into"),
            ("secondary_cutting_deviation", "mm", "deepest secondary cut"),
            ("check_tolerance", "mm", "grinding check tolerance"),
            ("round_trip_deviation", "mm", "wheel round trip"),
            ("wheel_radius_change", "mm", "wear"),
            ("max_normal_deviation", "mm", "largest normal deviation"),
            ("rms_normal_deviation", "mm", "rms normal deviation"),
            ("best_crossing_angle_change_deg", "deg", "crossing angle correction"),
            ("max_normal_deviation_compensated", "mm", "largest deviation, compensated"),
            ("rms_normal_deviation_compensated", "mm", "rms deviation, compensated"),
            ("deepest_cut_deviation", "mm", "deepest cut"),
            ("wheel_width", "mm", "wheel width"),
            ("bore_radius", "mm", "wheel bore radius"),
            ("shoulder_radius", "mm", "wheel shoulder radius"),
            # per unit of each setting error (rotorcad.grinding.sensitivity.UNITS): mm per mm, or per degree
            ("sensitivity.crossing_angle.max_normal_deviation_per_unit", "mm/deg", "deviation per degree of crossing angle"),
            ("max_normal_deviation_per_unit", "1", "deviation per mm of the setting error"),
            # the rows of grind's sensitivity table: the largest normal deviation per unit of each error
            ("sensitivity.center_distance", "mm/mm", "deviation per mm of centre distance"),
            ("sensitivity.crossing_angle", "mm/deg", "deviation per degree of crossing angle"),
            ("sensitivity.axial_position", "mm/mm", "deviation per mm of axial position"),
            ("sensitivity.wheel_radius", "mm/mm", "deviation per mm of wheel radius"),
            ("sensitivity.wheel_profile", "mm/mm", "deviation per mm of wheel profile"),
        ],
    ),
    # --- the gear as a part (rotorcad/gears/features.py, tip_corner.py, keys.py): `rotorcad gear`'s `features`
    (
        "rotorcad/gears",
        [
            (f"features{sep}{key}", unit, label)
            for key, unit, label in (
                ("tip_chamfer", "mm", "tip chamfer height h_K"),
                ("tip_rounding", "mm", "tip rounding radius r_K"),
                ("tip_land_half_angle_deg", "deg", "half angle of the tip land left"),
                ("tip_break_radius", "mm", "radius where the tip break meets the flank"),
                ("bore_diameter", "mm", "bore diameter"),
                ("rim_thickness", "mm", "rim under the bore or keyway"),
                ("hub_diameter", "mm", "hub diameter"),
                ("hub_length", "mm", "hub length"),
                ("keyway_width", "mm", "keyway width b (DIN 6885-1)"),
                ("keyway_height", "mm", "key height h (DIN 6885-1)"),
                ("keyway_shaft_depth", "mm", "keyway depth in the shaft t1 (DIN 6885-1)"),
                ("keyway_hub_depth", "mm", "keyway depth in the hub t2 (DIN 6885-1)"),
            )
            for sep in (".", "_")
        ],
    ),
    # --- a gear as the shop makes and checks it (rotorcad/gears/allowances.py, measurements.py, rack.py;
    # DIN 3967 / ISO 21771): nested figures are declared by their path and by the row name of the table
    (
        "rotorcad/gears",
        [
            (f"{key}{sep}{part}", unit, f"{label}, {part}")
            for key, parts, unit, label in _SHOP
            for part in parts
            for sep in (".", "_")
        ]
        + [
            ("span_teeth", "1", "teeth spanned"),
            ("span_contact_radius", "mm", "radius where the span touches"),
            ("pin_diameter", "mm", "pin or ball diameter"),
            ("pin_contact_radius", "mm", "radius where the pins touch"),
        ]
        + [
            (f"rack{sep}{key}", unit, f"rack {label}")
            for key, unit, label in (
                ("length", "mm", "length"),
                ("height", "mm", "height"),
                ("pitch", "mm", "transverse pitch"),
                ("normal_pitch", "mm", "normal pitch"),
                ("tooth_thickness", "mm", "tooth thickness at the datum line"),
                ("addendum", "mm", "addendum"),
                ("dedendum", "mm", "dedendum"),
                ("pressure_angle_deg", "deg", "pressure angle"),
                ("transverse_pressure_angle_deg", "deg", "transverse pressure angle"),
                ("teeth", "1", "teeth"),
                ("area", "mm²", "section area"),
            )
            for sep in (".", "_")
        ],
    ),
    # --- inspection from measured points (rotorcad/inspection/, rotorcad/cli/inspect_cmd.py; ISO 1328-1:2013) ---
    (
        "rotorcad/inspection",
        [
            ("points_read", "1", "points read"),
            ("points_on_flanks", "1", "points on the involute flanks"),
            ("alignment.rotation_deg", "deg", "best-fit rotation of the points"),
            ("alignment.rms_deviation", "mm", "rms normal deviation after the rotation"),
            ("evaluation_range.start_radius", "mm", "radius where L_alpha starts"),
            ("evaluation_range.end_radius", "mm", "radius where L_alpha ends"),
            ("evaluation_range.start_roll_length", "mm", "roll length where L_alpha starts"),
            ("evaluation_range.end_roll_length", "mm", "roll length where L_alpha ends"),
            ("evaluation_range.evaluation_length", "mm", "profile evaluation range L_alpha"),
            ("evaluation_range.start_roll_angle_deg", "deg", "roll angle where L_alpha starts"),
            ("evaluation_range.end_roll_angle_deg", "deg", "roll angle where L_alpha ends"),
            ("evaluation_range.tip_form_radius", "mm", "tip form radius"),
            ("evaluation_range.measuring_radius", "mm", "measuring circle of the pitch deviations"),
            ("teeth_measured[]", "1", "tooth measured"),
            ("flanks[].tooth", "1", "tooth"),
            ("flanks[].points_evaluated", "1", "points within L_alpha"),
            ("flanks[].position", "mm", "flank position on the measuring circle"),
            ("total_profile_deviation", "mm", "total profile deviation F_alpha"),
            ("profile_form_deviation", "mm", "profile form deviation f_falpha"),
            ("profile_slope_deviation", "mm", "profile slope deviation f_Halpha"),
            ("single_pitch_deviation", "mm", "single pitch deviation f_pt"),
            ("cumulative_pitch_deviation", "mm", "cumulative pitch deviation F_p over the teeth measured"),
            ("thickness_deviation[].tooth", "1", "tooth"),
            ("thickness_deviation[].deviation", "mm", "normal tooth thickness deviation"),
            ("thickness_deviation_mean", "mm", "mean normal tooth thickness deviation"),
            ("tolerance_class", "1", "ISO 1328-1 flank tolerance class"),
            ("single_pitch_tolerance", "mm", "single pitch tolerance f_pT"),
            ("cumulative_pitch_tolerance", "mm", "cumulative pitch tolerance F_pT"),
            ("profile_slope_tolerance", "mm", "profile slope tolerance f_HalphaT"),
            ("profile_form_tolerance", "mm", "profile form tolerance f_falphaT"),
            ("total_profile_tolerance", "mm", "total profile tolerance F_alphaT"),
            *(
                (f"classes.{key}", "1", f"finest class met by the {label}")
                for key, label in (
                    ("total_profile_deviation", "total profile deviation"),
                    ("profile_form_deviation", "profile form deviation"),
                    ("profile_slope_deviation", "profile slope deviation"),
                    ("single_pitch_deviation", "single pitch deviation"),
                    ("cumulative_pitch_deviation", "cumulative pitch deviation"),
                )
            ),
            ("lobes", "1", "lobes"),
            ("lobes_measured[]", "1", "lobe measured"),
            ("min_normal_deviation", "mm", "smallest normal deviation"),
            ("normal_deviation_range", "mm", "range of the normal deviation"),
            ("left.points", "1", "points on the left flanks"),
            ("right.points", "1", "points on the right flanks"),
        ],
    ),
]
