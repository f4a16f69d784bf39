"""The core of designs (issue 25): a design file becomes a spec, the spec a gear or a rotor pair,
every refusal a DesignError of its kind, named by the label table as the user typed it.

References: ISO 21771 (pitch diameter d = z m_n / cos beta); the gear sample's file as written
(samples/gear_pair.toml); the CLI's option table as it stood before the move (rotorcad/cli/gear.py
GEAR_OPTION, MATE_OPTION at commit ea1daf8), which the commands' messages were tested against.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rotorcad.design import load_gear_design, load_rotor_design, load_toml
from rotorcad.design.gears import GearSpec, build_gear, gear_spec
from rotorcad.design.labels import PairNames, contact_names, gear_name
from rotorcad.design.rotors import merge_pair
from rotorcad.errors import DesignError, GeometryError, InputFileError, MissingValueError

SAMPLES = Path(__file__).resolve().parents[1] / "samples"


def test_gear_spec_merges_the_design_and_the_given_values():
    """The sample's [gear] and [mate] as written, a given shift overriding the file's; the gear's pitch
    radius is ISO 21771's z m / 2 (spur)."""
    spec = gear_spec(load_gear_design(SAMPLES / "gear_pair.toml"), {"shift": 0.1, "module": None})
    assert (spec.teeth, spec.module, spec.shift, spec.mate_teeth, spec.mate_shift) == (17, 3.0, 0.1, 29, -0.1)
    assert "shift" not in spec.from_design and {"teeth", "module", "mate_teeth", "mate_shift"} <= spec.from_design
    gear, pair = build_gear(spec, 1e-3)
    assert gear.pitch_radius == pytest.approx(17 * 3.0 / 2) and pair.mate.pitch_radius == pytest.approx(29 * 3.0 / 2)
    with pytest.raises(AttributeError):
        spec.teeth = 18  # frozen


def test_gear_refusals_are_of_their_kind_and_named_as_typed():
    """No teeth: MissingValueError; bad mate teeth: ``mate.teeth``, named [mate] teeth when the file gave
    them, --mate-teeth when an option did; flanks apart at a centre distance of 10 m (the tip circles,
    of radii below 50 mm, cannot reach across it): GeometryError."""
    with pytest.raises(MissingValueError) as missing:
        gear_spec(None, {"module": 2.0})
    assert missing.value.param == "teeth" and isinstance(missing.value, DesignError)
    design = load_gear_design(SAMPLES / "gear_pair.toml")
    design["mate"]["teeth"] = 2
    with pytest.raises(DesignError) as bad:
        build_gear(gear_spec(design), 1e-3)
    assert bad.value.param == "mate.teeth"
    assert gear_name(bad.value.param, gear_spec(design).from_design) == "[mate] teeth"
    assert gear_name(bad.value.param, gear_spec(design, {"mate_teeth": 2}).from_design) == "--mate-teeth"
    with pytest.raises(GeometryError) as apart:
        build_gear(GearSpec(teeth=17, module=3.0, mate_teeth=29, mate_shift=-0.1, center_distance=1e4), 1e-3)
    assert apart.value.param == "contact_ratio" and "flanks meet" in str(apart.value)


def test_the_label_table_keeps_the_options_of_the_commands():
    """The CLI's option tables, derived now from the label table, are those the commands had."""
    from rotorcad.cli.gear import GEAR_OPTION, MATE_OPTION

    assert GEAR_OPTION == {
        "teeth": "--teeth",
        "module": "--module",
        "pressure_angle": "--pressure-angle",
        "helix_angle": "--helix-angle",
        "shift": "--shift",
        "addendum": "--addendum",
        "dedendum": "--dedendum",
        "tip_radius_factor": "--tip-radius",
        "tolerance": "--tolerance",
        "center_distance": "--center-distance",
        "radius": "radius",
        "face_width": "--face-width",
        # added with the tooth-thickness allowances, their measurements and the rack
        "thickness_allowance_upper": "--thickness-allowance-upper",
        "thickness_allowance_lower": "--thickness-allowance-lower",
        "span_teeth": "--span-teeth",
        "pin_diameter": "--pin-diameter",
        "rack_length": "--rack",
        "rack_height": "--rack-height",
        # added with internal gears and their shaper cutters
        "outer_diameter": "--outer-diameter",
        "cutter_teeth": "--cutter-teeth",
        "cutter_shift": "--cutter-shift",
        "cutter_tip_radius": "--cutter-tip-radius",
        "cutter_addendum": "--cutter-addendum",
    }
    assert MATE_OPTION == {
        "teeth": "--mate-teeth",
        "shift": "--mate-shift",
        "center_distance": "--center-distance",
        "shifts": "--shift and --mate-shift",
        "mesh": "--teeth, --mate-teeth, --shift, --mate-shift, --addendum and --pressure-angle",
        "thickness_allowance_upper": "--mate-thickness-allowance-upper",
        "thickness_allowance_lower": "--mate-thickness-allowance-lower",
    }
    assert contact_names(frozenset({"teeth", "mate_teeth"}), True) == (
        "[gear] teeth, [mate] teeth, --center-distance, --shift, --mate-shift, --addendum and --pressure-angle"
    )


def test_merge_pair_overrides_the_design_and_names_each_value_by_its_source():
    """The sample's [pair] with a given lead: the lead is the given one, the rest the file's; a bad
    value is named [pair] KEY when the file gave it, --KEY when an option did."""
    settings = load_rotor_design(SAMPLES / "rack_involute_5_6.toml")
    spec = merge_pair(settings, {"lead": 250.0, "speed_rpm": None})
    assert spec.pair.lead == 250.0 and spec.pair.male_teeth == settings["pair"]["male_teeth"]
    assert spec.family == "rack-involute" and spec.points is None
    settings["pair"]["male_tip_radius"] = 1.0  # inside the pitch circle
    with pytest.raises(DesignError) as bad:
        merge_pair(settings, {})
    names = PairNames(design=True, options=frozenset({"male_tip_radius"}))
    assert bad.value.param == "male_tip_radius"
    assert PairNames(design=True)(bad.value.param) == "[pair] male_tip_radius"
    assert names(bad.value.param) == "--male-tip-radius"
    with pytest.raises(MissingValueError):
        merge_pair(None, {"male_teeth": 5})


def test_a_file_that_cannot_be_read_is_an_input_file_error_with_the_sentence_it_had(tmp_path):
    """A missing file and malformed TOML: InputFileError (a DesignError, a ValueError), the sentences
    unchanged ("... must be an existing TOML design file (got PATH): there is no such file.")."""
    with pytest.raises(InputFileError) as missing:
        load_toml(tmp_path / "none.toml")
    path = tmp_path / "none.toml"
    assert str(missing.value) == f"design file must be an existing TOML design file (got {path}): there is no such file."
    bad = tmp_path / "bad.toml"
    bad.write_text("[pair\n")
    with pytest.raises(ValueError, match=r"^design file must be valid TOML"):
        load_toml(bad)


def test_the_public_sweep_takes_the_analyses_it_is_given(tmp_path):
    """``rotorcad.sweep(...)`` runs in the core: with no analyses given for hobbability it refuses
    naming [sweep] compute; the registered ones (the entry point ``hob`` of rotorcad.extensions,
    pyproject.toml) hold hob's verdict."""
    import rotorcad
    from rotorcad.sweep.files import registered_analyses
    from rotorcad.sweep.plan import Extra

    base = (SAMPLES / "rack_involute_5_6.toml").resolve()
    sweep_file = tmp_path / "s.toml"
    sweep_file.write_text(f'[sweep]\nbase = "{base}"\ncompute = ["hobbability"]\n[vary]\n"pair.lead" = [250.0, 300.0]\n')
    with pytest.raises(DesignError, match=r"^\[sweep\] compute must be analyses this run can make \(got hobbability\)"):
        rotorcad.sweep(sweep_file, workers=0, analyses={})
    assert Extra.HOBBABILITY in registered_analyses(), "pip install -e . again: the entry points of rotorcad.extensions"
    calls = []

    def verdict(rotors, spec, clearance):
        calls.append(spec.pair.lead)
        return {"hobbable": True, "hob_reason": ""}

    table = rotorcad.sweep(sweep_file, workers=0, analyses={Extra.HOBBABILITY: verdict})
    assert sorted(calls) == [250.0, 300.0] and list(table["pair.lead"]) == [250.0, 300.0] and np.all(table["hobbable"])


def test_a_given_smoothing_overrides_the_design_like_every_other_value():
    """The rule of the commands ("options given on the command line override" the design file): the
    design's [profile] smoothing gave way to --smoothing nowhere before the merge moved to the core."""
    from rotorcad.design import rotor_design

    mapping = load_toml(SAMPLES / "rack_involute_5_6.toml")
    mapping["profile"] = {"family": "male-points", "points": "male.csv", "smoothing": 0.5}
    settings = rotor_design(mapping, SAMPLES)
    assert merge_pair(settings, {}).smoothing == 0.5
    assert merge_pair(settings, {"smoothing": 0.0}).smoothing == 0.0
