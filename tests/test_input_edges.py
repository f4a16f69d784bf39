"""Regression tests for the examples of issue 15 ("Every input gets an answer"): each test names
the example it covers. Fast: refusals come before any heavy work."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorcad.cli.main import main

SAMPLES = Path(__file__).resolve().parent.parent / "samples"
ASYM = SAMPLES / "srm_asymmetric_5_6.toml"
SYM_PAIR = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--male-tip-radius", "54"]
SYM_PAIR += ["--male-root-radius", "40", "--female-tip-radius", "60", "--female-root-radius", "46", "--lead", "260"]
SYM_PAIR += ["--length", "150"]


def run(capsys, *argv: str) -> tuple[int, str, str]:
    capsys.readouterr()
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert "Traceback" not in err
    return status, out, err


def refused(capsys, needle: str, *argv: str) -> str:
    status, _, err = run(capsys, *argv)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert status == 2 and len(lines) == 1 and needle in lines[0], err
    return lines[0]


def design(tmp_path: Path, text: str | bytes, name: str = "d.toml") -> Path:
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


def sym_points(tmp_path: Path, rotor: str) -> np.ndarray:
    run_ok = main(["rotor", str(SAMPLES / "srm_symmetric_4_6.toml"), f"--{rotor}-csv", str(tmp_path / f"{rotor}.csv")])
    assert run_ok == 0
    return np.loadtxt(tmp_path / f"{rotor}.csv", delimiter=",", comments="#", skiprows=2)


def write_points(path: Path, pts: np.ndarray) -> Path:
    path.write_text("x,y\n" + "\n".join(f"{float(x)!r},{float(y)!r}" for x, y in pts) + "\n")
    return path


# ----- crashes and hangs ----------------------------------------------------------------------
def test_crash_export_every_dimension_x1000(capsys, tmp_path):
    """Crash: the srm-asymmetric sample x1000, `rotorcad export` (segfault at 12.7 GB). x1000 (a
    116 m centre distance) is now refused by the 100 m bound of a design length; x300 (lead 90 m,
    length 57 m) still reaches the estimate of the triangles."""
    bound = "[pair] center_distance must be a positive length up to 100000 mm"
    for scale, needle in ((1000, bound), (300, "tolerance must be at least")):
        text = ASYM.read_text()
        for key in ("center_distance", "male_tip_radius", "male_root_radius", "female_tip_radius", "female_root_radius", "lead"):
            text = re.sub(rf"^{key} = ([0-9.]+)", lambda m, k=key, s=scale: f"{k} = {float(m.group(1)) * s}", text, flags=re.M)
        text = re.sub(r"^length = ([0-9.]+)", f"length = {190.0 * scale}", text, flags=re.M)
        line = refused(capsys, needle, "export", design(tmp_path, text), "--out", tmp_path / "out")
        assert scale == 1000 or "million triangles" in line
        assert not (tmp_path / "out").exists()  # no folder left


def test_crash_interfere_check_3d_lead_0_001(capsys, tmp_path):
    """Crash: `lead = 0.001` with `interfere --steps 8 --tolerance 1.0 --check-3d`."""
    path = design(tmp_path, re.sub(r"^lead = .*$", "lead = 0.001", ASYM.read_text(), flags=re.M))
    refused(capsys, "[pair] lead must be at least", "interfere", path, "--steps", "8", "--tolerance", "1.0", "--check-3d")


@pytest.mark.parametrize("command", ["hob", "rotor", "gear", "cut", "interfere", "deflect"])
def test_hang_fifo_design_path(capsys, tmp_path, command):
    """Hang: a design path that is a FIFO (`hob` opened it before checking it)."""
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    refused(capsys, "pipe or device", command, fifo)


def test_hang_dxf_writer_500_teeth(capsys, tmp_path):
    """Hang: `gear --teeth 500 --module 5 --csv g.csv --dxf g.dxf` (ezdxf appended point by point)."""
    status, _, _ = run(
        capsys, "gear", "--teeth", "500", "--module", "5", "--csv", tmp_path / "g.csv", "--dxf", tmp_path / "g.dxf"
    )
    assert status == 0 and (tmp_path / "g.dxf").stat().st_size > 1e6


def test_hang_rotor_female_points_with_noise(capsys, tmp_path):
    """Hang: `rotor --female-points` with 0.1 mm of noise on the symmetric sample's points."""
    pts = sym_points(tmp_path, "female")
    noisy = write_points(tmp_path / "noisy.csv", pts + np.random.default_rng(2).uniform(-0.1, 0.1, pts.shape))
    line = refused(capsys, "--female-points must be points that scatter by at most", "rotor", "--female-points", noisy, *SYM_PAIR)
    assert "--smoothing" in line  # refused by the scatter now, before the fit (a smooth profile's limit came after it)


@pytest.mark.parametrize(("seed", "noise", "smoothing"), [(76, 0.15, "0"), (77, 0.1, "1e-9"), (89, 0.1, None), (49, 0.15, "1")])
def test_slow_noisy_female_points_refused_before_the_sections(capsys, tmp_path, seed, noise, smoothing):
    """Slow (up to 120 s): `rotor --female-points` with 0.1-0.15 mm of noise on the symmetric
    sample's female; the generated male folded into 8 000-20 000 points a lobe, which made its
    section take minutes, and the numbers that came out were the noise's (a contact line 30 times
    the clean one's). Refused before the sections are made: with a smoothing given, by the points a
    smooth lobe can have; without, by the scatter itself (seed 89 folded the male less than the
    smooth-lobe limit and was accepted with the noise's numbers)."""
    from rotorcad.cli.rotor import _build

    opts = dict.fromkeys(["male_points", "female_points", "rack_points", "layer", "smoothing", "speed"])
    pts = _build(SAMPLES / "srm_symmetric_4_6.toml", opts)[0].female_outline().points
    noisy = pts + np.random.default_rng(seed).uniform(-noise, noise, pts.shape)
    path = write_points(tmp_path / "noisy.csv", noisy)
    extra = [] if smoothing is None else ["--smoothing", smoothing]
    line = refused(capsys, "--female-points must be ", "rotor", "--female-points", path, *SYM_PAIR, *extra)
    assert "--smoothing" in line
    if smoothing is not None:
        # a smoothing below n sigma^2 over a lobe's points follows the scatter: refused by it as without one
        # (rotorcad.design.rotors._refuse_scatter); at least that, by the points a smooth lobe can have
        smooth = "a smooth profile" in line and "points in a lobe (a smooth lobe has at most" in line
        assert smooth or "points that scatter by at most" in line, line
        return
    # uniform noise of half-width w has the standard deviation w / sqrt(3) (57.7 um for 0.1 mm): the
    # scatter named is that within 15 % (the estimate of rotorcad.measured.outline.scatter); the most
    # allowed is (h / 4)^2 / (16 a) for the female's lobe depth h = 60 - 46 mm at a = 100 mm: 7.66 um
    got = float(re.search(r"a scatter of ([0-9.]+) µm", line).group(1))
    assert got == pytest.approx(1e3 * noise / np.sqrt(3.0), rel=0.15)
    assert "at most 7.66 µm" in line


def test_smooth_lobe_points_leave_room_for_every_sample():
    """The limit on a generated lobe's points is three times a generous estimate; the samples' lobes
    (built from their racks) have at most 40 % of the estimate (an eighth of the limit: the
    rack-involute female, with two tip-corner paths and two tip circles, has 36 %)."""
    from rotorcad.cli.rotor import _build
    from rotorcad.rotor_build import smooth_lobe_points

    opts = dict.fromkeys(["male_points", "female_points", "rack_points", "layer", "smoothing", "speed"])
    for sample in sorted(SAMPLES.glob("srm_*.toml")) + [SAMPLES / "rack_involute_5_6.toml", SAMPLES / "lysholm_4_6.toml"]:
        rotors = _build(sample, opts)[0]
        p = rotors.pair
        for lobe, tip, teeth in (
            (rotors.male_lobe(), p.male_tip_radius, p.male_teeth),
            (rotors.female_lobe(), p.female_tip_radius, p.female_teeth),
        ):
            assert sum(len(s.points) for s in lobe.segments) < 0.4 * smooth_lobe_points(tip, teeth), sample.name


def test_hang_cut_module_50_helical_pointed(capsys):
    """Hang: `cut --teeth 100 --module 50 --helix-angle 15 --shift -2 --addendum 3 --tip-radius 0
    --mate-teeth 4 --center-distance 2574` (the refinement grew to 57 000 positions): now bounded, and
    a shift below -addendum is refused."""
    argv = ["cut", "--teeth", "100", "--module", "50", "--helix-angle", "15", "--shift", "-2", "--addendum", "3"]
    argv += ["--tip-radius", "0", "--mate-teeth", "4", "--center-distance", "2574"]
    status, out, _ = run(capsys, *argv, "--json")
    assert status in (0, 2)
    if status == 0:
        result = json.loads(out)
        assert result["tolerance_met"] == (result["max_deviation_from_envelope"] <= 1e-3)


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["cut", "--teeth", "20", "--module", "2", "--tolerance", "1e-9"], "--tolerance must be at least"),
        (["cut", "--teeth", "20", "--module", "1e9"], "--module must be"),
        (["interfere", str(ASYM), "--tolerance", "1e-9"], "--tolerance must be at least"),
    ],
)
def test_memory_cut_and_interfere_tiny_tolerance_huge_module(capsys, argv, needle):
    """10 GB runs: `cut --tolerance 1e-9`, `cut --module 1e9`, `interfere --tolerance 1e-9`."""
    refused(capsys, needle, *argv)


# ----- tracebacks on valid-looking inputs ---------------------------------------------------
def test_traceback_cut_teeth_3(capsys):
    """`cut --teeth 3 --module 25` (GEOSException in hob/cutting.py, then a refusal): now cut, and its
    undercut point agrees with the analytic one (the pitch circle of z = 3 lies on the fillet: the
    involute was taken from there, and the simulated P' was 2 mm off for z = 4 as well)."""
    for teeth in ("3", "4"):
        status, out, err = run(capsys, "cut", "--teeth", teeth, "--module", "25", "--json")
        assert status == 0, err
        res = json.loads(out)
        assert res["tolerance_met"] and res["max_deviation_from_envelope"] <= 1e-3
        assert res["undercut_radius"] == pytest.approx(res["undercut_radius_exact"], abs=3e-3)


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        # the fillets of both flanks meet inside the tooth: an outline that crosses itself was written
        # by `gear`, and `cut` ended in an internal error (GEOSException)
        (["gear", "--teeth", "3", "--module", "0.3", "--shift", "-0.2", "--tip-radius", "0"], "--shift must be from -0.0"),
        (["cut", "--teeth", "3", "--module", "0.3", "--shift", "-0.2", "--tip-radius", "0"], "--shift must be from -0.0"),
        (["gear", "--teeth", "4", "--module", "1", "--shift", "-0.5"], "cut its head off"),
        # pointed before the involute starts: the fillet runs past the tooth's centre line
        (["gear", "--teeth", "12", "--module", "1", "--shift", "3"], "--shift must be at most 2.53"),
        (["pump", "--teeth", "12", "--module", "1", "--shift", "2.8", "--face-width", "5", "--speed", "100"], "--shift must"),
    ],
)
def test_gear_whose_outline_crosses_itself_is_refused(capsys, argv, needle):
    refused(capsys, needle, *argv)


def test_traceback_cut_pitch_circle_outside_tooth(capsys):
    """`cut --teeth 400 --module 0.25 --shift -1.5` (zero-size array in cut_cmd._half_angle)."""
    refused(capsys, "--shift must be greater than -1", "cut", "--teeth", "400", "--module", "0.25", "--shift", "-1.5")


def test_traceback_latin1_byte_in_design_and_points(capsys, tmp_path):
    """A Latin-1 byte anywhere in a design or points file, even in a comment (UnicodeDecodeError)."""
    path = design(tmp_path, ASYM.read_bytes().replace(b"# Asymmetric", b"# Asym\xe9trique"))
    assert run(capsys, "rotor", path, "--json")[0] == 0
    pts = sym_points(tmp_path, "female")
    body = write_points(tmp_path / "f.csv", pts).read_bytes()
    (tmp_path / "latin.csv").write_bytes(b"# Me\xdfpunkte\n" + body)
    assert run(capsys, "rotor", "--female-points", tmp_path / "latin.csv", *SYM_PAIR, "--json")[0] == 0


@pytest.mark.parametrize("kind", ["duplicated", "identical", "collinear"])
def test_traceback_duplicated_identical_collinear_points(capsys, tmp_path, kind):
    """Duplicated or identical points (`curves.fit`), collinear points (`meshing.cusp`)."""
    pts = sym_points(tmp_path, "female")
    x = np.linspace(0.0, 10.0, 50)
    spoilt = {"duplicated": np.repeat(pts, 2, axis=0), "identical": np.tile(pts[:1], (50, 1)), "collinear": np.c_[x, 2 * x + 1]}
    path = write_points(tmp_path / "p.csv", spoilt[kind])
    status, _, err = run(capsys, "rotor", "--female-points", path, *SYM_PAIR, "--json")
    assert status == 0 or (status == 2 and "--female-points" in err)


@pytest.mark.parametrize("value", ["-1", "nan", "inf"])
def test_negative_or_nan_smoothing_refused(capsys, tmp_path, value):
    """Negative smoothing ("Invalid inputs."), and `--smoothing nan` / `-1` accepted."""
    pts = write_points(tmp_path / "f.csv", sym_points(tmp_path, "female"))
    refused(capsys, "--smoothing", "rotor", "--female-points", pts, *SYM_PAIR, "--smoothing", value)


def test_radial_clearance_nan(capsys, tmp_path):
    """`radial_clearance = nan`."""
    path = design(tmp_path, ASYM.read_text().replace("radial_clearance = 0.05", "radial_clearance = nan"))
    refused(capsys, "[housing] radial_clearance", "rotor", path)


def test_output_name_over_255_bytes(capsys, tmp_path):
    """An output name over 255 bytes (OSError in exports/atomic.py)."""
    refused(
        capsys,
        "--csv must be a file name of at most 255 bytes",
        "gear",
        "--teeth",
        "20",
        "--module",
        "2",
        "--csv",
        tmp_path / ("a" * 300),
    )
    assert list(tmp_path.iterdir()) == []


def test_shift_1e30_module_1e300_teeth_1e20_hob_module_1e_12(capsys, tmp_path):
    """`shift = 1e30`, `--module 1e300`, teeth 1e20, `hob --module 1e-12`."""
    path = design(tmp_path, (SAMPLES / "gear_pair.toml").read_text().replace("shift = 0.3", "shift = 1e30"))
    refused(capsys, "[gear] shift", "gear", path)  # the key as the file names it
    refused(capsys, "--module must be a length from", "gear", "--teeth", "20", "--module", "1e300")
    refused(capsys, "--teeth must be a whole number from 3 to", "gear", "--teeth", str(10**20), "--module", "1")
    refused(capsys, "--module must be a length from", "hob", "--teeth", "20", "--module", "1e-12")


# ----- wrong numbers with exit 0 --------------------------------------------------------------
def test_pump_negative_flow(capsys):
    """`pump --teeth 9 --module 1 --shift -1.5 --face-width 5 --speed 100`: negative mean flow."""
    refused(capsys, "--shift", "pump", "--teeth", "9", "--module", "1", "--shift", "-1.5", "--face-width", "5", "--speed", "100")


def test_pump_with_a_contact_ratio_below_one_is_refused(capsys):
    """`pump --teeth 9 --module 3` (x = 0) reported eps = 0.665 and a delivery that jumps at the
    pitch end as success. A gear pump needs eps >= 1 (Kollek & Osinski Fig. 4, the eps = 1 line).
    z = 9 unshifted is undercut (below z = 2 / sin^2 alpha = 17), so its usable involute starts
    above the base circle and the contact ratio is below the tip-to-tip ISO 21771 value."""
    pump = ("pump", "--teeth", "9", "--module", "3", "--face-width", "20", "--speed", "1500")
    line = refused(capsys, "contact ratio of at least 1", *pump)
    assert re.search(r"got 0\.66", line)
    # with x = 0.5 (no undercut: x >= 1 - z sin^2(alpha) / 2 = 0.47) it delivers, and its contact
    # ratio is ISO 21771's closed form for two equal shifted gears: inv a_w = inv a + 2 x tan a / z,
    # a_w = z m cos a / cos a_w, eps = (2 sqrt(ra^2 - rb^2) - a_w sin a_w) / (pi m cos a)
    z, m, x, alpha = 9, 3.0, 0.5, np.radians(20.0)
    inv_w = np.tan(alpha) - alpha + 2 * x * np.tan(alpha) / z
    alpha_w = brentq(lambda a: np.tan(a) - a - inv_w, 0.01, 1.4, xtol=1e-15)
    a_w = z * m * np.cos(alpha) / np.cos(alpha_w)
    rb, ra = z * m / 2 * np.cos(alpha), z * m / 2 + m * (1 + x)
    eps = (2 * np.sqrt(ra**2 - rb**2) - a_w * np.sin(alpha_w)) / (np.pi * m * np.cos(alpha))
    status, out, _ = run(capsys, *pump, "--shift", "0.5", "--json")
    assert status == 0 and json.loads(out)["contact_ratio"] == pytest.approx(eps, abs=1e-9)


def test_contact_ratio_zero_is_refused(capsys):
    """`contact_ratio: 0.0` as success: `gear --pressure-angle 1` with a mate; `gear --teeth 12
    --module 2 --shift -0.5 --mate-teeth 4` (working pressure angle 0)."""
    refused(
        capsys, "contact ratio above 0", "gear", "--teeth", "20", "--module", "2", "--pressure-angle", "1", "--mate-teeth", "30"
    )
    refused(capsys, "contact ratio above 0", "gear", "--teeth", "12", "--module", "2", "--shift", "-0.5", "--mate-teeth", "4")


def test_undercut_true_with_null_radius(capsys):
    """`cut --teeth 8 --module 0.1 --tolerance 1`: `undercut: true` with `undercut_radius: null`."""
    refused(capsys, "--tolerance must be at most", "cut", "--teeth", "8", "--module", "0.1", "--tolerance", "1")
    status, out, _ = run(capsys, "cut", "--teeth", "8", "--module", "0.1", "--tolerance", "0.01", "--json")
    result = json.loads(out)
    assert status == 0 and result["undercut"] and result["undercut_radius"] > 0


def test_backlash_never_null(capsys):
    """`backlash: null` (infinite backlash of teeth that never meet) is refused, not printed."""
    status, out, _ = run(
        capsys, "gear", "--teeth", "20", "--module", "2", "--mate-teeth", "30", "--center-distance", "60", "--json"
    )
    assert status == 2 or json.loads(out)["backlash"] is not None


def test_hob_root_radius_of_a_straight_piece_is_infinite(capsys):
    """`hob_root_radius` of 1e12-1e13 for a straight rack piece: null plus a flag (CONTRACT.md)."""
    status, out, _ = run(capsys, "hob", SAMPLES / "gear_pair.toml", "--json")
    rack = json.loads(out)["racks"]["gear"]
    assert status == 0 and rack["hob_root_radius"] is None and rack["hob_root_radius_infinite"] is True
    assert rack["hob_tip_radius_infinite"] is False and 0 < rack["hob_tip_radius"] < 1e6


def test_clearance_mean_at_lead_1e9(capsys, tmp_path):
    """Clearance `mean_clearance: null` at lead 1e9."""
    m = write_points(tmp_path / "m.csv", sym_points(tmp_path, "male"))
    f = write_points(tmp_path / "f.csv", sym_points(tmp_path, "female"))
    argv = ["clearance", "--male-points", m, "--female-points", f, "--male-teeth", "4", "--female-teeth", "6"]
    status, out, _ = run(capsys, *argv, "--center-distance", "100", "--lead", "1e9", "--json")
    assert status == 2 or json.loads(out)["mean_clearance"] is not None


@pytest.mark.parametrize("command", [["cut"], ["gear"], ["rotor", str(ASYM)], ["interfere", str(ASYM)]])
def test_tolerance_inf_refused(capsys, command):
    """`--tolerance inf` accepted."""
    extra = ["--teeth", "20", "--module", "2"] if command[0] in ("cut", "gear") else []
    refused(capsys, "--tolerance", *command, *extra, "--tolerance", "inf")


# ----- messages -------------------------------------------------------------------------------
def test_messages_name_tip_radius_and_profile_keys(capsys, tmp_path):
    """Messages name `--tip-radius` and `[profile] lobe_width`-style keys, not internal names."""
    refused(capsys, "--tip-radius", "gear", "--teeth", "20", "--module", "2", "--tip-radius", "5")
    text = ASYM.read_text().replace('family = "srm-asymmetric"', 'family = "sigma"')
    refused(capsys, "[profile] family", "rotor", design(tmp_path, text))
    refused(
        capsys, "[profile] seal_stop", "rotor", design(tmp_path, ASYM.read_text().replace("seal_stop = 0.9", "seal_stop = 5.0"))
    )


def test_bare_rotorcad_prints_help(capsys):
    """A bare `rotorcad` printed the whole help squashed into one error line."""
    status, out, err = run(capsys)
    assert status == 0 and out.startswith("Usage: rotorcad") and err == ""


def test_unwritable_output_names_the_option(capsys):
    """An unwritable output under /proc named a hidden temporary file instead of the option."""
    line = refused(
        capsys, "--csv must be a file that can be written", "gear", "--teeth", "20", "--module", "2", "--csv", "/proc/x.csv"
    )
    assert ".tmp" not in line


def test_dxf_r12_no_warning(capsys, tmp_path):
    """`dxf-r12` printed an ezdxf warning on stderr on success."""
    status, _, err = run(capsys, "export", ASYM, "--out", tmp_path / "o", "--format", "dxf-r12", "--quiet")
    assert status == 0 and err == ""


def test_failed_run_leaves_no_out_folder(capsys, tmp_path):
    """29 failed runs left an empty `--out` folder they created."""
    refused(capsys, "--dxf", "gear", "--teeth", "20", "--module", "2", "--out", tmp_path / "a" / "b", "--dxf", "/proc/x.dxf")
    assert list(tmp_path.iterdir()) == []


# ----- interference as an exit code -----------------------------------------------------------
def test_interfere_exit_status(capsys):
    """`interfere` exits 0 when clean and 1 when it finds interference beyond its threshold."""
    assert run(capsys, "interfere", ASYM, "--steps", "8")[0] == 0
    status, out, _ = run(capsys, "interfere", ASYM, "--steps", "8", "--center-distance", "110", "--json")
    assert status == 1 and json.loads(out)["interferes"] is True


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        # found by the long fuzz run (ROTORCAD_FUZZ_EXAMPLES=800): both were internal errors
        (
            ["gear", "--teeth", "17", "--module", "2", "--pressure-angle", "1.3344119962731866e-139"],
            "--pressure-angle must be from 1",
        ),
        (
            ["cut", "--teeth", "12", "--module", "2", "--tip-radius", "0", "--hob-addendum", "1e-09"],
            "--hob-addendum must be from 0.1",
        ),
        # the 20 000-case run: a film that underflowed to 0 was divided by (ZeroDivisionError)
        (
            ["coupling", "--teeth", "66", "--speed", "1.1125369292536007e-308", "--misalignment-deg", "0.9168647369500968"]
            + ["--json", "--module", "3", "--face-width", "20", "--viscosity", "0.05", "--power", "50"]
            + ["--pressure-viscosity", "2e-8"],
            "--speed must be a number from 0.1 to 1e6",
        ),
        (
            ["coupling", "--teeth", "40", "--speed", "1500", "--misalignment-deg", "0.1", "--module", "1e-300"]
            + ["--face-width", "20", "--viscosity", "0.05", "--power", "50", "--pressure-viscosity", "2e-8"],
            "--module must be a number from 0.1 to 100",
        ),
        # the 20 000-case run: sampling the tool to 1e-198 mm asked for an array too big to exist
        (["cut", "--teeth", "12", "--module", "2", "--tolerance", "3.057997538222402e-198"], "--tolerance must be at least 3.3"),
    ],
)
def test_long_fuzz_findings_are_refused_in_one_sentence(capsys, argv, words):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


def test_more_long_fuzz_findings(tmp_path, capsys):
    # deflect with a lead that wraps the rotors many times ran past two minutes: refused (at most 720 deg)
    root = Path(__file__).resolve().parents[1]
    design = tmp_path / "lead.toml"
    design.write_text((root / "samples" / "rack_involute_5_6.toml").read_text().replace("lead = 300.0", "lead = 20.0"))
    assert main(["deflect", str(design)]) == 2
    assert "[pair] lead must be one that gives a male wrap of at most 720 degrees" in capsys.readouterr().err
    # coupling's "error in the input data" names the options that caused it
    args = ["coupling", "--face-width", "0.1", "--teeth", "40", "--module", "3", "--speed", "1500", "--viscosity", "0.05"]
    args += ["--power", "50", "--misalignment-deg", "0.1", "--pressure-viscosity", "2e-8"]
    assert main(args) == 2
    err = capsys.readouterr().err  # R_b = b / (4 tan gamma) = 14.3 mm < r (1 + sin alpha) = 80.5 mm
    assert "--misalignment-deg must be below" in err and "or --face-width above" in err


def test_cut_writes_the_whole_gear(capsys, tmp_path):
    """Found while bounding cut's memory: the simulated gear of --csv and --dxf was the union of the z
    turned tooth sectors, which did not fuse (one tooth came out) and, for 1000 teeth, took 30 s and
    1.5 GB; it is now tooth 0's outline turned and chained. The whole outline matches the analytic
    gear to the scallop height."""
    import shapely

    from rotorcad.gear import DEG, InvoluteGear

    for teeth in ("7", "1000"):
        path = tmp_path / f"g{teeth}.csv"
        status, _, err = run(capsys, "cut", "--teeth", teeth, "--module", "1", "--tolerance", "0.01", "--csv", path)
        assert status == 0, err
        simulated = shapely.Polygon(np.loadtxt(path, delimiter=",", comments="#", skiprows=2))
        analytic = shapely.Polygon(InvoluteGear(int(teeth), 1.0, 20 * DEG).outline(1e-3).points)
        assert simulated.is_valid
        if teeth == "7":  # (quadratic in the points)
            assert shapely.hausdorff_distance(simulated.exterior, analytic.exterior) < 0.02
        assert 0 <= simulated.area - analytic.area < 0.01 * analytic.length  # cutting leaves scallops, never less


def test_gear_design_keys_are_named_by_their_table(capsys, tmp_path):
    """A bad `[gear] shift` in a design file was reported as `--shift`, an option the user never typed;
    an option given beside the file is still named as the option."""
    path = tmp_path / "g.toml"
    path.write_text("[gear]\nteeth = 3\nmodule = 2.0\nshift = -0.5\n")
    refused(capsys, "[gear] shift", "gear", str(path))
    refused(capsys, "--shift", "gear", str(path), "--shift", "-0.6")
    path.write_text("[gear]\nteeth = 20\nmodule = 2.0\n[mate]\nteeth = 30\nshift = 9.0\n")
    refused(capsys, "[mate] shift", "gear", str(path))


@pytest.fixture(scope="module")
def symmetric_design_outlines():
    """The srm-symmetric sample's design male and female, whole, as shapely lines (0.1 um chord)."""
    import tomllib

    import shapely

    from rotorcad.design import rotor_design
    from rotorcad.geometry import rotate
    from rotorcad.rotor_build import build_pair, pair_spec

    spec = pair_spec(rotor_design(tomllib.loads((SAMPLES / "srm_symmetric_4_6.toml").read_text()), SAMPLES))
    rotors = build_pair(spec)
    out = {}
    for side, teeth in (("male", 4), ("female", 6)):
        lobe = np.vstack([seg.resampled(1e-4).points for seg in getattr(rotors, f"{side}_lobe")().segments])
        out[side] = shapely.MultiLineString([rotate(lobe, k * 2 * np.pi / teeth) for k in range(teeth)])
    return out


def test_near_duplicate_points_keep_their_corners(capsys, symmetric_design_outlines):
    """The long fuzz run's case wq7zryhc: the symmetric sample's male and female, the female with 0.5 um
    of normal scatter and its points in pairs 0.3-3 um apart on its tip land. The chords across such a
    pair point anywhere (0.5 um of scatter over 0.3 um), and they were read as four more sharp
    corners (16 where there are 12): `clearance --contact driving` refused ("the racks never touch
    there"), `--contact sealing` read -3.55 mm of interference. Reference: the design pair is
    conjugate (Rinder Fig. 3's rack, a semicircle, generates both rotors: no clearance on the contact
    zone), and the given points lie within d_max of the design's outlines (shapely, measured here):
    each contact reads within d_max of 0, without interference; the female has two sharp corners a
    lobe (where its circular flanks meet its tip circle, the pitch circle: 12)."""
    import shapely

    from rotorcad.measured.outline import corners, read_outline

    data = Path(__file__).resolve().parent / "reference_data" / "fuzz"
    male, female = (data / f"clearance_wq7zryhc_{side}.csv" for side in ("male", "female"))
    given = np.loadtxt(female, delimiter=",", skiprows=1)
    outline = read_outline(given, 6, "--female-points")
    assert len(corners(outline.whole, outline.sigma)[0]) == 12
    d_max = max(
        float(
            shapely.distance(shapely.points(np.loadtxt(path, delimiter=",", skiprows=1)), symmetric_design_outlines[side]).max()
        )
        for side, path in (("male", male), ("female", female))
    )
    assert d_max < 1.5e-3  # the points as the fuzz run kept them
    pair = ["--male-teeth", "4", "--female-teeth", "6", "--center-distance", "100", "--json", "--quiet"]
    for contact in ("driving", "sealing", "as-given"):
        status, out, err = run(capsys, "clearance", "--male-points", male, "--female-points", female, *pair, "--contact", contact)
        assert status == 0, (contact, err)
        result = json.loads(out)
        assert not result["interference"], contact
        assert -d_max <= result["min_normal_clearance"] <= result["max_normal_clearance"] <= d_max, (contact, result)
