"""A sweep's figures against the full single-design analysis (``rotorcad rotor --json``).

A sweep row is computed by :func:`rotorcad.sweep.figures.sweep_figures`, which skips what a row
does not hold and takes the flute areas from the outline's own polygon instead of clipping it to a
2048-gon (:data:`rotorcad.sweep.figures.FLUTE_AREA_RTOL`). The reference is the command itself,
run on a design file of each variant: ``rotorcad rotor FILE --json`` (its ``analyse_pair`` and
``MeshingAnalysis.summary``, shapely's clipped sections). Every other column must be the command's
number bit for bit; the flute areas, the displacement and the area utilisation within
FLUTE_AREA_RTOL; a variant the command refuses is a row with the command's sentence.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import tomli_w

from rotorcad.cli.main import main
from rotorcad.design import load_toml
from rotorcad.sweep.figures import FLUTE_AREA_RTOL
from rotorcad.sweep.plan import apply, sweep_plan
from rotorcad.sweep.tasks import RESULT_COLUMNS, clear_cache, evaluate

SAMPLES = Path(__file__).resolve().parents[1] / "samples"
EXACT = ("meshline_closed", "blow_hole_area", "contact_line_length", "max_sliding_velocity", "wrap_angle_deg")
EXACT += ("rack_loss_percent", "runs_without_timing_gears")
AREAS = ("male_flute_area", "female_flute_area", "displacement_per_rev", "area_utilisation")

# a few variants of several families: lead and length (the section kept), a tip radius and the
# centre distance (a new section; some of them refused by the family)
VARIANTS = {
    "rack_involute_5_6": {"profile.lobe_width": [0.4, 0.66], "pair.lead": [250.0, 340.0]},
    "lysholm_4_6": {"pair.male_root_radius": [None, -0.5], "pair.length": [150.0]},
    "srm_asymmetric_5_6": {"pair.center_distance": [None, 1.0], "pair.lead": [300.0]},
    "n_rack_5_6": {"pair.female_tip_radius": [None, -0.3], "pair.lead": [280.0]},
    "krigar_4_6": {"pair.lead": [260.0, 330.0]},
    "srm_b_5_6": {"pair.male_tip_radius": [None, -0.4]},
}


def _sweep_data(name: str, base: dict) -> dict:
    """The [vary] table of a family's variants: ``None`` the base's value, a number beside "pair.*_radius" an offset."""
    vary = {}
    for key, values in VARIANTS[name].items():
        table, _, sub = key.partition(".")
        offsets = key.endswith("_radius") or key.endswith("center_distance")
        vary[key] = [base[table][sub] + (v or 0.0) if offsets else v for v in values]
    return {"vary": vary}


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_sweep_figures_are_those_of_rotor_json_within_the_stated_tolerance(name, tmp_path, capsys):
    base = load_toml(SAMPLES / f"{name}.toml")
    plan = sweep_plan(_sweep_data(name, base), base)
    clear_cache()
    rows = [evaluate(plan.base, None, None, (), v) for v in plan.variants()]
    assert len(rows) >= 2
    for variant, row in zip(plan.variants(), rows, strict=True):
        design = tmp_path / f"{name}_{variant.index}.toml"
        design.write_text(tomli_w.dumps(apply(plan.base, variant.values)))
        code = main(["rotor", str(design), "--json"])
        out, err = capsys.readouterr()
        if not row["ok"]:
            assert code == 2 and row["reason"] in err  # the command refuses it with the same sentence
            continue
        assert code == 0, err
        reference = json.loads(out)
        for key in EXACT:
            assert row[RESULT_COLUMNS[key]] == reference[key], key
        for key in AREAS:
            assert row[RESULT_COLUMNS[key]] == pytest.approx(reference[key], rel=FLUTE_AREA_RTOL, abs=0), key
        for slip in ("max_slip_male", "max_slip_female"):  # an infinite slip: JSON null and value_infinite
            assert row[slip] == (float("inf") if reference[slip]["value_infinite"] else reference[slip]["value"])
        kinds = [d["kind"] for d in reference["defects"]]
        assert row["defects"] == len(kinds)
        assert row["defect_kinds"] == ", ".join(sorted(set(kinds)))
        for kind in ("cusp", "jamming", "slipping"):
            assert row[f"defects_{kind}"] == kinds.count(kind)
    assert any(r["ok"] for r in rows)


def test_meshline_contact_is_that_of_the_full_conjugate():
    # Generated.meshline_contact skips the generated points; its t and meshline must be those of
    # Generated.contact (the full conjugate) and its rack points and tangents those of Curve.evaluate
    import numpy as np

    from rotorcad.design.rotors import build_pair, pair_spec
    from rotorcad.design.schema import rotor_design
    from rotorcad.envelope import Generated

    for name in ("rack_involute_5_6", "lysholm_4_6", "srm_symmetric_4_6"):
        rotors = build_pair(pair_spec(rotor_design(load_toml(SAMPLES / f"{name}.toml"), None)))
        mesh = rotors.pair.mesh
        for piece in rotors.rack:
            gen = Generated(piece.curve, mesh.rack, mesh.female)
            s = np.linspace(piece.curve.s0, piece.curve.s1, 101)
            full = gen.contact(s)
            t, x, p, tan = gen.meshline_contact(s)
            ref_p, ref_tan = piece.curve.evaluate(s)
            np.testing.assert_array_equal(t, full.t)
            np.testing.assert_array_equal(x, full.meshline)
            np.testing.assert_array_equal(p, ref_p)
            np.testing.assert_array_equal(tan, ref_tan)


def test_the_median_of_the_defect_tests_is_numpys():
    # meshing._median replaces np.median in the defect tests: the same number (numpy the reference)
    import numpy as np

    from rotorcad.meshing.defects import _median

    rng = np.random.default_rng(3)
    for n in (1, 2, 3, 600, 601):
        values = np.abs(rng.normal(size=n))
        assert _median(values) == float(np.median(values))
    assert np.isnan(_median(np.array([1.0, np.nan, 2.0])))


@pytest.mark.parametrize("driving_width", [0.3, 0.5, 0.7, 0.9, 1.25])
def test_tip_check_refuses_exactly_where_the_lobe_made_valid_falls_short(driving_width):
    # check_tips measures the lobe's joined points and skips make_valid when they form a valid
    # polygon; the reference is the brute-force way: the raw samples of every segment closed
    # through the centre, made valid by shapely, the largest part's farthest point
    import numpy as np
    import shapely

    from rotorcad.errors import DesignError
    from rotorcad.families.checks import check_tips
    from rotorcad.families.n_rack import n_rack
    from rotorcad.rotor_pair import RotorPair

    pair = RotorPair(5, 6, 82.0, 57.99, 35.66, 46.34, 24.01, lead=300.0, length=162.079)  # test_families' PAIR_N4
    rotors = n_rack(pair, driving_width=driving_width)
    short = False
    for lobe, tip in ((rotors.male_lobe(), pair.male_tip_radius), (rotors.female_lobe(), pair.female_tip_radius)):
        raw = np.vstack([[0.0, 0.0]] + [seg.points for seg in lobe.segments if len(seg.points)])
        parts = shapely.get_parts(shapely.make_valid(shapely.Polygon(raw)))
        while any(g.geom_type in ("MultiPolygon", "GeometryCollection") for g in parts):
            parts = shapely.get_parts(parts)
        body = max((g for g in parts if g.geom_type == "Polygon"), key=lambda g: g.area)
        short |= float(np.hypot(*np.asarray(body.exterior.coords).T).max()) < tip - 1e-3
    if short:
        with pytest.raises(DesignError):
            check_tips(rotors)
    else:
        check_tips(rotors)  # the sample's 1.25 passes, test_families' 0.3 is refused: both branches run


def _sample_racks():
    """The racks of a few samples' pairs (straight, circular and point-path pieces), built once."""
    from rotorcad.design.rotors import build_pair, pair_spec
    from rotorcad.design.schema import rotor_design

    names = ("rack_involute_5_6", "lysholm_4_6", "n_rack_5_6", "srm_asymmetric_5_6")
    return [build_pair(pair_spec(rotor_design(load_toml(SAMPLES / f"{name}.toml"), None))) for name in names]


def test_one_pass_contacts_are_those_of_each_piece():
    # envelope.meshline_contacts solves the contact of all rack pieces in one pass; reference: the
    # engine's own per-piece Generated.meshline_contact, element for element (bit for bit)
    import numpy as np

    from rotorcad.envelope import Generated, meshline_contacts

    for rotors in _sample_racks():
        mesh = rotors.pair.mesh
        gens = [Generated(piece.curve, mesh.rack, mesh.female) for piece in rotors.rack]
        params = [np.linspace(g.parent.s0, g.parent.s1, 37 + 5 * k) for k, g in enumerate(gens)]
        for joint, (g, s) in zip(meshline_contacts(gens, params), zip(gens, params, strict=True), strict=True):
            for got, ref in zip(joint, g.meshline_contact(s), strict=True):
                np.testing.assert_array_equal(got, ref)


def test_one_pass_meshline_is_that_of_piece_by_piece():
    # meshing.meshline_pieces resamples and masks all pieces together; reference: the per-piece
    # way written out here (even_meshline_contact of each piece, its contacts inside both bores
    # within 1 um, the lobe part of each kept point), compared bit for bit
    import numpy as np

    from rotorcad.envelope import Generated
    from rotorcad.meshing.meshline import even_meshline_contact, flank_roles, meshline_pieces

    for rotors in _sample_racks():
        pair = rotors.pair
        mesh, o2 = pair.mesh, np.array([pair.center_distance, 0.0])
        reference = []
        for index, piece in enumerate(rotors.rack):
            gen = Generated(piece.curve, mesh.rack, mesh.female)
            s, (t, x, rack_pts, tan) = even_meshline_contact(gen, piece.curve.s0, piece.curve.s1, 600, pair.center_distance)
            inside = (np.hypot(*x.T) <= pair.male_tip_radius + 1e-3) & (np.hypot(*(x - o2).T) <= pair.female_tip_radius + 1e-3)
            ok = np.isfinite(t) & inside & np.all(np.isfinite(x), axis=1)
            if ok.sum() >= 2:
                roles = flank_roles(rack_pts[ok], tan[ok], pair.male_pitch_radius, pair.center_distance)
                reference.append((index, s[ok], t[ok], x[ok], tan[ok], roles))
        got = meshline_pieces(rotors.rack, pair, 600)
        assert [p.rack_index for p in got] == [r[0] for r in reference]
        for piece, (_, s, t, x, tan, roles) in zip(got, reference, strict=True):
            for a, b in ((piece.s, s), (piece.t, t), (piece.points, x), (piece.tangents, tan)):
                np.testing.assert_array_equal(a, b)
            assert list(piece.roles) == list(roles)


def test_scalar_rack_line_contact_is_the_engines():
    # envelope.rack_line_meshline_point (the tip-corner root search's function) against the
    # engine's array evaluation Generated.meshline_contact at the same parameter, bit for bit,
    # inside and beyond every straight piece, both ways of travel
    import numpy as np

    from rotorcad.envelope import Generated, rack_line_meshline_point

    rng = np.random.default_rng(5)
    checked = 0
    for rotors in _sample_racks():
        mesh = rotors.pair.mesh
        for piece in rotors.rack:
            for curve in (piece.curve, piece.curve.reversed()):
                for generated in (mesh.female, mesh.male):
                    gen = Generated(curve, mesh.rack, generated)
                    point = rack_line_meshline_point(gen)
                    if point is None:
                        continue
                    lo, hi = sorted((curve.s0, curve.s1))
                    for v in rng.uniform(lo - 1.0, hi + 1.0, 40):
                        np.testing.assert_array_equal(np.array(point(float(v))), gen.meshline_contact(float(v))[1][0])
                        checked += 1
    assert checked > 500


def test_row_norms_are_numpys():
    # geometry.row_norms replaces np.linalg.norm(v, axis=1) in the meshline tangents and the
    # contact line; numpy the reference, bit for bit, over magnitudes from 1e-8 to 1e3
    import numpy as np

    from rotorcad.geometry import row_norms

    rng = np.random.default_rng(7)
    for k in (2, 3):
        v = rng.normal(size=(20000, k)) * 10.0 ** rng.integers(-8, 4, size=(20000, 1))
        np.testing.assert_array_equal(row_norms(v), np.linalg.norm(v, axis=1))


def test_the_median_bound_of_the_defect_tests_is_numpys():
    # meshing.defects._median_below answers "median < bound" by a count where it can; numpy's
    # median the reference, at bounds on and either side of the median, with NaNs
    import numpy as np

    from rotorcad.meshing.defects import _median_below

    rng = np.random.default_rng(11)
    for n in (*range(1, 12), 600, 601):
        for _ in range(40):
            values = np.abs(rng.normal(size=n)) * rng.choice([1e-9, 1.0, 1e3])
            if rng.random() < 0.2:
                values[rng.integers(n)] = np.nan
            middle = float(np.median(values[np.isfinite(values)])) if np.isfinite(values).any() else 1.0
            for bound in (middle, np.nextafter(middle, 0.0), np.nextafter(middle, np.inf), float(rng.random())):
                assert _median_below(values, bound) == bool(np.median(values) < bound)


def test_local_cluster_workers_start_lean_and_keep_the_users_settings():
    # sweep.run._lean_workers: what the local cluster's nanny hands its workers (dask's config, read
    # back through dask.config.get, the reference): no per-task stack profiler, a 1 s tick, no
    # MALLOC_TRIM_THRESHOLD_ before spawning; the other pre-spawn variables and the user's own
    # settings kept, and everything as it was afterwards
    import dask
    import distributed  # noqa: F401 - loads distributed's defaults into dask.config

    from rotorcad.sweep.run import LEAN_WORKERS, _lean_workers

    before = dask.config.get("distributed.nanny.pre-spawn-environ")
    profiled = dask.config.get("distributed.worker.profile.enabled")
    assert "MALLOC_TRIM_THRESHOLD_" in before
    with dask.config.set({"distributed.nanny.pre-spawn-environ.MY_SETTING": "kept"}), _lean_workers():
        spawn = dask.config.get("distributed.nanny.pre-spawn-environ")
        assert "MALLOC_TRIM_THRESHOLD_" not in spawn
        assert spawn["MY_SETTING"] == "kept" and spawn["OMP_NUM_THREADS"] == before["OMP_NUM_THREADS"]
        assert dask.config.get("distributed.worker.profile.enabled") is False
        for key, value in LEAN_WORKERS.items():
            assert dask.config.get(key) == value
    assert dask.config.get("distributed.nanny.pre-spawn-environ") == before
    assert dask.config.get("distributed.worker.profile.enabled") == profiled
