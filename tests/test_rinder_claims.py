"""Rinder's claims about his profile families, checked on rotorcad's samples.

Each test reads the numbers of ``rotorcad rotor SAMPLE --json`` (the same dict, from
:func:`rotorcad.rotor_build.design_summary`) and names the sentence of Rinder, *Sonderverzahnungen
für Schraubenverdichterrotoren*, that it checks (sec. 1.2 the families, 2.2.1 the meshline rules,
2.2.2 tightness, 3.2 the comparison of the 5:6 narrow-tip and rack-involute pairs at a = 116 mm).
The references are the paper's words and closed forms computed here from the design file (the
overlap ratio z1 L / h, radii, base circles), never rotorcad's own output.
"""

from __future__ import annotations

import functools
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rotorcad.rotor_build import design_summary

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def _design(name: str) -> dict:
    with (SAMPLES / f"{name}.toml").open("rb") as f:
        return tomllib.load(f)


@functools.cache
def summary(name: str, length: float | None = None) -> dict:
    """The ``rotor --json`` numbers of a sample (optionally with another rotor length, mm)."""
    design = _design(name)
    if length is not None:
        design["pair"]["length"] = length
    return design_summary(design, SAMPLES)


def overlap_ratio(name: str, length: float | None = None) -> float:
    """Rinder's Sprungüberdeckung from the design file: wrap angle 2 pi L / h over the pitch 2 pi / z1."""
    pair = _design(name)["pair"]
    return pair["male_teeth"] * (length or pair["length"]) / pair["lead"]


def flank(name: str, which: str) -> dict:
    return summary(name)["flanks"][which]


# ---- Krigar (Fig. 1) --------------------------------------------------------------------------


def test_krigar_has_no_geometric_contact_and_does_not_run():
    # sec. 1.2: "Eine Berührung der Flanken ... im geometrischen Sinn mit gemeinsamen Tangenten ...
    # ist in keinem Flankenteil gegeben" and "Die Verzahnung ist nicht lauffähig".
    s = summary("krigar_4_6")
    for which in ("driving", "sealing"):
        f = s["flanks"][which]
        assert f["working_length"] == 0.0 and f["geometric_share"] == 0.0
        assert not f["runs_without_timing_gears"]
    assert not s["runs_without_timing_gears"]
    assert len(s["running_reasons"]) == 2 and all("no geometric contact" in r for r in s["running_reasons"])


def test_krigar_meshline_is_closed_without_blow_hole():
    # sec. 1.2: "Die Eingriffslinie ... ist geschlossen und reicht bis zum Schnittpunkt der
    # Läuferkopfkreise ... Die Zahnlücken sind dicht und ohne Blasloch."
    s = summary("krigar_4_6")
    assert s["meshline_closed"] and s["blow_hole_area"] == 0.0


# ---- Lysholm (Fig. 2) -------------------------------------------------------------------------


def test_lysholm_driving_flank_runs_by_the_helix_alone():
    # sec. 1.2: "Dieses Profil ist an der Triebflanke einwandfrei lauffähig. Die nur infinitesimale
    # Stirnüberdeckung wird durch ... hohe Sprungüberdeckung kompensiert." Reference: the overlap
    # ratio z1 L / h from the design file.
    f = flank("lysholm_4_6", "driving")
    assert f["transverse_contact_ratio"] == pytest.approx(0.0, abs=1e-9)  # infinitesimal
    assert f["overlap_contact_ratio"] == pytest.approx(overlap_ratio("lysholm_4_6"), rel=1e-12)
    assert f["total_contact_ratio"] >= 1.0
    assert f["working_length"] > 0 and f["defects"] == [] and f["runs_without_timing_gears"]


def test_lysholm_driving_circle_about_c_is_not_jamming():
    # sec. 2.2.1: a normal through C is jamming, "Eine Ausnahme stellt nur jener Fall dar, wo beide
    # Flankenkrümmungsmittelpunkte mit dem Wälzpunkt zusammenfallen, wie dies ... beim
    # Lysholmprofil der Fall ist."
    s = summary("lysholm_4_6")
    assert not [d for d in s["defects"] if d["kind"] == "jamming"]


def test_lysholm_sealing_flank_seals_but_needs_timing_gears():
    # sec. 1.2: "Die Dichtflanke hat kein Blasloch" and "Auch dieses Profil ist, da es ... auch an der
    # Dichtflanke immer wieder zur Flankenberührung kommt, ohne Koppelgetriebe nicht einwandfrei
    # verwendbar." Its sealing flank is the Krigar flank: point-generated only.
    s = summary("lysholm_4_6")
    assert s["blow_hole_area"] == 0.0 and s["meshline_closed"]
    seal = s["flanks"]["sealing"]
    assert seal["working_length"] == 0.0 and not seal["runs_without_timing_gears"]
    assert not s["runs_without_timing_gears"]


def test_cusps_at_tip_corners_are_the_corners_not_defects():
    # sec. 2.2.2: "Am Haupt- bzw. Nebenläuferkopf ist demnach nur eine Spitze oder Ecke als Flanke
    # denkbar"; sec. 2.2.1 names these cusps in the runnable profiles ("vgl. Bild 1, 2, 3 und 4").
    # Every cusp of the Lysholm and SRM samples lies on a tip circle (radius from the design file).
    for name in ("lysholm_4_6", "srm_symmetric_4_6", "srm_asymmetric_5_6"):
        s = summary(name)
        pair = _design(name)["pair"]
        cusps = [d for d in s["defects"] if d["kind"] == "cusp"]
        assert cusps and all(d["tip_corner"] for d in cusps), name
        for d in cusps:
            if d["point_generated"]:
                continue
            r1 = np.hypot(d["x"], d["y"])
            r2 = np.hypot(d["x"] - pair["center_distance"], d["y"])
            assert min(abs(r1 - pair["male_tip_radius"]), abs(r2 - pair["female_tip_radius"])) < 0.02, name


# ---- symmetric SRM (Fig. 3) -------------------------------------------------------------------


def test_symmetric_srm_runs_in_both_directions_given_enough_wrap():
    # sec. 1.2: "Die Lauffähigkeit ist bei ausreichender Verschraubung der Zähne in beiden
    # Drehrichtungen gegeben." Both flanks are circles about C (transverse ratio 0, no jamming by
    # the exception of 2.2.1): they run when the overlap z1 L / h reaches 1, not below.
    s = summary("srm_symmetric_4_6")
    assert s["runs_without_timing_gears"]
    for which in ("driving", "sealing"):
        f = s["flanks"][which]
        assert f["transverse_contact_ratio"] == pytest.approx(0.0, abs=1e-9)
        assert f["total_contact_ratio"] == pytest.approx(overlap_ratio("srm_symmetric_4_6"), rel=1e-12)
        assert f["runs_without_timing_gears"]
    short = 0.8 * _design("srm_symmetric_4_6")["pair"]["lead"] / 4  # overlap 0.8: too little wrap
    s = summary("srm_symmetric_4_6", short)
    assert s["flanks"]["driving"]["total_contact_ratio"] == pytest.approx(0.8, rel=1e-9)
    assert not s["runs_without_timing_gears"]
    assert all("too little wrap" in r for r in s["running_reasons"]) and len(s["running_reasons"]) == 2


# ---- asymmetric SRM (Fig. 4) and SRM-B --------------------------------------------------------


def test_asymmetric_srm_sealing_flank_runs_over_a_small_region():
    # sec. 1.2: "gab der Dichtflanke zumindest in einem kleinen Flankenbereich einwandfreie
    # Laufeigenschaften, indem man ... ein kurzes Stück Geradflanke einbaute"; the driving flank is
    # Lysholm's ("praktisch wieder zum asymmetrischen Lysholmprofil zurück").
    s = summary("srm_asymmetric_5_6")
    seal, drive = s["flanks"]["sealing"], s["flanks"]["driving"]
    assert 0 < seal["working_length"] < 0.3 * seal["meshline_length"]  # a small region
    assert seal["runs_without_timing_gears"] and seal["defects"] == []
    assert drive["transverse_contact_ratio"] == pytest.approx(0.0, abs=1e-9) and drive["runs_without_timing_gears"]


def test_srm_b_runs_without_timing_gears_with_more_transverse_overlap_and_a_shorter_meshline():
    # sec. 1.2: "Der Mittelpunkt der Kreisbogenflanke liegt jetzt nicht mehr im Wälzpunkt C ... Dies
    # führt zu einer weiteren Verkürzung der Eingriffslinienlänge ... Überdies wird die Überdeckung
    # im Stirnschnitt vergrößert. Das so entstandene asymmetrische SRM-B-Profil ist gut ohne
    # Koppelgetriebe lauffähig".
    a, b = summary("srm_asymmetric_5_6"), summary("srm_b_5_6")
    assert b["flanks"]["driving"]["transverse_contact_ratio"] > a["flanks"]["driving"]["transverse_contact_ratio"] + 0.1
    assert b["flanks"]["driving"]["meshline_length"] < a["flanks"]["driving"]["meshline_length"]
    assert b["runs_without_timing_gears"] and b["running_reasons"] == []


def _hob(capsys, name: str) -> dict:
    from rotorcad.cli.main import main

    assert main(["hob", str(SAMPLES / f"{name}.toml"), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_srm_b_hobs_badly_and_the_rack_involute_well(capsys):
    # sec. 1.2: SRM-B "hat aber den Nachteil, daß es schlecht wälzfräsbar ist"; the rack profile:
    # "Gute Wälzfräsbarkeit mit einfachen Werkzeugen wird angestrebt"; sec. 2.1: "Die
    # Wälzfräsbarkeit ist durch die Beurteilung des zugehörigen Zahnstangenprofils möglich." The
    # SRM-B male's rack (rotorcad hob) stands perpendicular to the pitch line at the driving arc's
    # foot; the rack-involute's rack flanks are straight at their pressure angles (a simple tool).
    srm_b = _hob(capsys, "srm_b_5_6")
    assert not srm_b["hobbable"]
    assert any("flank angle falls" in r for r in srm_b["reasons"])
    involute = _hob(capsys, "rack_involute_5_6")
    assert not any("flank angle" in r for r in involute["reasons"])


# ---- narrow-tip (Fig. 5) ----------------------------------------------------------------------


def test_narrow_tip_runs_on_both_flanks_with_long_point_generated_sealing_parts():
    # sec. 1.2: "kurze Eingriffslinien an der Triebflanke, aber immer noch lange, punkterzeugte
    # Flankenteile an der Dichtflanke ... mit hoher relativer Dichtigkeit und guten
    # Laufeigenschaften an beiden Flankenteilen."
    s = summary("narrow_tip_5_6")
    drive, seal = s["flanks"]["driving"], s["flanks"]["sealing"]
    assert drive["runs_without_timing_gears"] and seal["runs_without_timing_gears"]
    point_generated = seal["meshline_length"] - seal["working_length"]
    assert point_generated > seal["working_length"]  # long point-generated sealing parts
    assert drive["meshline_length"] < seal["meshline_length"] / 2  # short driving meshline
    assert [f for f in s["point_generated_flanks"] if f["rotor"] == "female"]


# ---- rack-involute (Fig. 6) -------------------------------------------------------------------


def test_rack_involute_obeys_the_laws_of_gearing_everywhere_and_runs():
    # sec. 1.2: "der Verzahnung in jedem Eingriffspunkt gute Lauffähigkeit und einwandfreie
    # kinematische Verhältnisse zu geben"; sec. 3.2: "Beim Zahnstangenprofil sind die
    # Verzahnungsgesetze in allen Punkten erfüllt". No cusp or jamming inside a working flank.
    s = summary("rack_involute_5_6")
    assert s["runs_without_timing_gears"]
    for which in ("driving", "sealing"):
        assert s["flanks"][which]["defects"] == []
    assert all(d["tip_corner"] for d in s["defects"] if d["kind"] == "cusp")


def test_rack_involute_has_infinite_slip_at_one_single_point_on_the_base_circle():
    # sec. 3.2: "Hier gibt es nur in einem einzigen Punkt unendliche Schlupfwerte. Dies rührt daher,
    # daß die Evolventenflanke bis zum Grundkreis benutzt wurde" and "lediglich die
    # Dichtflankenevolvente wird beim Nebenläufer bis zur Spitze ausgenutzt". Reference: the female
    # base circle r2w cos(alpha_s) from the design file; the involute's point there is its cusp.
    d = _design("rack_involute_5_6")
    pair, prof = d["pair"], d["profile"]
    r2w = pair["center_distance"] * pair["female_teeth"] / (pair["male_teeth"] + pair["female_teeth"])
    base = r2w * np.cos(np.radians(prof["sealing_angle_deg"]))
    s = summary("rack_involute_5_6")
    sing = s["slip_singularities"]
    assert len(sing) == 1
    assert sing[0]["rotor"] == "female" and sing[0]["flank"] == "sealing"
    assert sing[0]["female_radius"] == pytest.approx(base, abs=1e-3)


def test_blow_holes_in_rinders_order():
    # sec. 1.2 and 2.2.2: Krigar "ohne Blasloch", Lysholm's sealing flank "hat kein Blasloch"; the
    # symmetric SRM profile "ein relativ großes Blasloch"; asymmetric SRM "ein kleines Blasloch";
    # narrow-tip: "Die Blaslöcher können klein gehalten werden, sind aber unvermeidlich"; the rack
    # profile "das auch hier unvermeidliche Blasloch möglichst klein". Compared as a share of the
    # flute areas (the samples differ in size); "<<" read as a third at most.
    share = {}
    for name in ("krigar_4_6", "lysholm_4_6", "narrow_tip_5_6", "srm_asymmetric_5_6", "rack_involute_5_6", "srm_symmetric_4_6"):
        s = summary(name)
        share[name] = s["blow_hole_area"] / (s["male_flute_area"] + s["female_flute_area"])
    assert share["krigar_4_6"] == 0.0 and share["lysholm_4_6"] == 0.0
    small = [share[n] for n in ("narrow_tip_5_6", "srm_asymmetric_5_6", "rack_involute_5_6")]
    assert all(v > 0 for v in small)
    assert max(small) < share["srm_symmetric_4_6"] / 3


def test_flute_areas_like_real_compressors():
    # Rinder's figures (1-6): male and female flutes of the same order; a nearly solid female is no
    # compressor rotor. Female over male flute area between 1/3 and 3 for every family sample.
    for name in (
        "krigar_4_6",
        "lysholm_4_6",
        "srm_symmetric_4_6",
        "srm_asymmetric_5_6",
        "srm_b_5_6",
        "narrow_tip_5_6",
        "rack_involute_5_6",
    ):
        s = summary(name)
        assert 1 / 3.5 < s["female_flute_area"] / s["male_flute_area"] < 3, name


# ---- sec. 3.2: the comparison at a = 116 mm ---------------------------------------------------


def test_sliding_velocities_of_narrow_tip_and_rack_involute_about_equal():
    # sec. 3.2: "Ermittelt man den Verlauf der Gleitgeschwindigkeiten (Bild 10 und 11) so erkennt
    # man, daß diese für beide Profile etwa gleich sind" (read: within +-25 %). Both pairs 5:6 at
    # a = 116 mm, 3000 rpm.
    n, r = summary("narrow_tip_5_6"), summary("rack_involute_5_6")
    for s in (n, r):
        assert (s["male_teeth"], s["female_teeth"], s["center_distance"]) == (5, 6, 116.0)
    assert r["max_sliding_velocity"] == pytest.approx(n["max_sliding_velocity"], rel=0.25)


def test_largest_sliding_velocity_at_the_male_tip_near_minus_25_degrees():
    # sec. 3.2: "Die größte Gleitgeschwindigkeit tritt am Hauptläuferkopf ... an der Dichtflanke auf.
    # Die größte Freßgefahr besteht demnach für eine Drehwinkelstellung von ca. -25° für die
    # Dichtflanke am Nebenläuferkopf und für den Hauptläuferkopf." Angle in the one convention of
    # rotorcad (CONTRACT.md), read as "about" = within 8 degrees.
    for name in ("narrow_tip_5_6", "rack_involute_5_6"):
        s = summary(name)
        at = s["max_sliding_at"]
        tip = _design(name)["pair"]["male_tip_radius"]
        assert at["flank"] == "sealing", name
        assert at["male_radius"] == pytest.approx(tip, abs=0.02 * tip), name
        assert at["angle_deg"] == pytest.approx(-25.0, abs=8.0), name


def test_the_readme_shows_rotorcads_numbers_beside_rinders_words():
    # The README's table "Rinder says | rotorcad now" is the samples' current `rotor --json` numbers
    # (samples/rinder_comparison/compare.py formats them), not a stale copy.
    import importlib.util

    spec = importlib.util.spec_from_file_location("compare", SAMPLES / "rinder_comparison" / "compare.py")
    compare = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(compare)
    readme = (SAMPLES.parent / "README.md").read_text()
    assert compare.verdict_table({name: summary(name) for name in compare.VERDICT_SAMPLES}) in readme


# ---- infinite slip: from positions, and from the female's points (issue 21 item 3) ----------------


def test_tangential_lever_is_the_foot_of_the_perpendicular():
    # Rinder eq. 2: v_t = omega N P, N the foot of the perpendicular from the rotor's centre on the contact
    # normal (a line through C). Reference: N found by projecting O onto a straight line of action through C at
    # 26 deg (the rack-involute's sealing angle), the involute's case: N P = |P - T|, T the base circle's tangency
    from rotorcad.meshing.slip import tangential_lever

    a, r1w = 116.0, 116.0 * 5 / 11
    c, o2 = np.array([r1w, 0.0]), np.array([a, 0.0])
    direction = np.array([np.sin(np.radians(26.0)), np.cos(np.radians(26.0))])
    s = np.linspace(-20.0, 30.0, 101)
    s = s[np.abs(s) > 1e-9]
    points = c + s[:, None] * direction
    foot = c + ((o2 - c) @ direction) * direction  # T: the female base circle's point on the line
    lever, gain = tangential_lever(points, o2, c)
    np.testing.assert_allclose(np.abs(lever), np.hypot(*(points - foot).T), atol=1e-12)
    assert np.hypot(*(foot - o2)) == pytest.approx(a * 6 / 11 * np.cos(np.radians(26.0)), rel=1e-12)  # r2w cos 26 deg
    assert np.all(gain >= 1.0)


def test_a_corner_off_its_pitch_circle_moves_the_zero_from_c_as_the_square_root():
    # the reason a given female tip corner on its pitch circle (SRM, Krigar, Lysholm) made points of infinite slip
    # near C: its corner placed dr inside the pitch circle runs on a circle that meets the Thales circle on O2 C
    # where cos(theta) = (r2w - dr) / r2w (closed form), sqrt(2 r2w dr) from C; on the pitch circle itself, at C only
    from rotorcad.meshing.slip import tangential_lever

    a, r2w, dr = 116.0, 116.0 * 6 / 11, 50e-3
    c, o2 = np.array([a - r2w, 0.0]), np.array([a, 0.0])
    theta = np.linspace(1e-4, 0.2, 20001)
    circle = o2 + (r2w - dr) * np.column_stack([-np.cos(theta), np.sin(theta)])
    lever = tangential_lever(circle, o2, c)[0]
    (k,) = np.flatnonzero(lever[:-1] * lever[1:] < 0)
    expected = np.arccos((r2w - dr) / r2w)
    assert theta[k] == pytest.approx(expected, abs=2e-5)
    assert np.hypot(*(circle[k] - c)) == pytest.approx(np.sqrt(2 * r2w * dr), rel=0.01)
    on_pitch = o2 + r2w * np.column_stack([-np.cos(theta), np.sin(theta)])
    assert not np.any(tangential_lever(on_pitch, o2, c)[0][:-1] * tangential_lever(on_pitch, o2, c)[0][1:] < 0)


def test_rack_involute_from_its_females_points_has_its_one_point_of_infinite_slip():
    # sec. 3.2 "nur in einem einzigen Punkt unendliche Schlupfwerte ... Evolventenflanke bis zum Grundkreis" from the
    # female's exact points, 300 a lobe (a CMM's scan): 0 before (the fit rounds the meshline's corner where the male
    # tip corner's path meets the involute's line of action, and the rounded meshline passed 0.15 mm from the zero
    # without crossing it). Reference: the female base circle r2w cos(alpha_s) from the design file, within the
    # input's resolution sqrt(8 a e) (rotorcad.meshing.resolution)
    from independent_pairs import scan

    from rotorcad.design import rotor_design
    from rotorcad.meshing import resolution
    from rotorcad.rotor_build import PairSpec, analyse_pair, build_pair, pair_spec

    d = _design("rack_involute_5_6")
    spec = pair_spec(rotor_design(d, SAMPLES))
    outline = np.asarray(build_pair(spec).section("female", tolerance=1e-5).exterior.coords)[:-1]
    points = scan(outline, spec.pair.female_teeth * 300, 0.37)
    given = build_pair(PairSpec(spec.pair, "female-points", {}, points, None, spec.speed_rpm, 0.0), label="--female-points")
    s = analyse_pair(given, spec.speed_rpm)[1]
    pair, prof = d["pair"], d["profile"]
    r2w = pair["center_distance"] * pair["female_teeth"] / (pair["male_teeth"] + pair["female_teeth"])
    base = r2w * np.cos(np.radians(prof["sealing_angle_deg"]))
    (sing,) = s["slip_singularities"]
    assert sing["rotor"] == "female" and sing["flank"] == "sealing"
    assert sing["female_radius"] == pytest.approx(base, abs=resolution(s["defect_accuracy"], pair["center_distance"]))
