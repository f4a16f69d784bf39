"""A command pays only for the libraries it uses (issue 26, item 1).

Each command runs in a fresh interpreter that then prints the modules it loaded; the heavy ones a
command does not need must be absent. Reference: the libraries each output needs, as documented in
exports.meshes (STL, OBJ and PLY by numpy; trimesh only for 3MF, GLB and checks; meshio for VTU and
XDMF) and exports.background (OpenCASCADE in the writer process).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from exports.background import worker_count

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "samples" / "rack_involute_5_6.toml"
# heavy libraries (import time on the reference machine): trimesh 0.6-1 s with scipy.spatial and
# networkx, OpenCASCADE 1.1 s, scipy.optimize 0.3 s, scipy.interpolate 0.35 s, matplotlib, pandas, dask
HEAVY = (
    "trimesh",
    "OCP",
    "networkx",
    "meshio",
    "matplotlib",
    "pandas",
    "dask",
    "distributed",
    "h5py",
    "scipy.optimize",
    "scipy.interpolate",
    "scipy.spatial",
    "scipy.ndimage",
)

RUN = """
import json, sys
from rotorcad.cli.main import main
try:
    main({args!r})
except SystemExit:
    pass
sys.stdout.flush()
print("\\nMODULES", json.dumps(sorted(sys.modules)))
"""


def loaded_modules(args: list[str], cwd: Path) -> set[str]:
    """Run ``rotorcad ARGS`` in a fresh interpreter and return the names of the modules it loaded."""
    proc = subprocess.run(
        [sys.executable, "-c", RUN.format(args=args)], cwd=cwd, capture_output=True, text=True, timeout=600, check=True
    )
    line = next(x for x in proc.stdout.splitlines() if x.startswith("MODULES "))
    return set(json.loads(line.removeprefix("MODULES ")))


RUN_WITH_WORKER = """
import json, sys
import multiprocessing.util
import exports.background as background
start = background._start_worker

def start_and_record(*args):
    # the worker writes the modules it holds when it ends (after its jobs)
    def record():
        with open({record!r}, "w") as f:
            json.dump(sorted(sys.modules), f)
    multiprocessing.util.Finalize(None, record, exitpriority=100)
    start(*args)

background._start_worker = start_and_record
from rotorcad.cli.main import main
try:
    main({args!r})
except SystemExit:
    pass
sys.stdout.flush()
print("\\nMODULES", json.dumps(sorted(sys.modules)))
"""


def command_and_worker_modules(args: list[str], cwd: Path) -> tuple[set[str], set[str] | None]:
    """Run ``rotorcad ARGS`` in a fresh interpreter; return the modules it loaded and those its writer process held at its end.

    The second is None when the command had no writer process (one core).
    """
    record = cwd / "worker_modules.json"
    proc = subprocess.run(
        [sys.executable, "-c", RUN_WITH_WORKER.format(args=args, record=str(record))],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=600,
        check=True,
    )
    line = next(x for x in proc.stdout.splitlines() if x.startswith("MODULES "))
    worker = set(json.loads(record.read_text())) if record.exists() else None
    return set(json.loads(line.removeprefix("MODULES "))), worker


def heavy_in(modules: set[str]) -> set[str]:
    return {h for h in HEAVY if h in modules}


@pytest.fixture(scope="module")
def short_design(tmp_path_factory) -> Path:
    """The README sample, 30 mm long (the same imports, less sweeping)."""
    path = tmp_path_factory.mktemp("design") / "short.toml"
    path.write_text(SAMPLE.read_text().replace("length = 190.0", "length = 30.0"))
    return path


def test_export_of_numpy_mesh_formats_imports_no_trimesh_meshio_or_ocp(short_design, tmp_path):
    args = ["export", str(short_design), "--format", "stl,stl-ascii,obj,ply,csv", "--tolerance", "0.1"]
    modules = loaded_modules([*args, "--out", str(tmp_path / "o"), "--json", "--quiet"], tmp_path)
    assert (tmp_path / "o" / "short_male.stl").exists() and (tmp_path / "o" / "short_female.ply").exists()
    assert heavy_in(modules) == set()


def test_readme_export_leaves_opencascade_to_the_writer_process(short_design, tmp_path):
    # the README's main job: the design's formats stl, step and dxf; with a worker (two cores or
    # more) OpenCASCADE and ezdxf load there only, without one (one core) here, and the files are the same
    modules, worker = command_and_worker_modules(
        ["export", str(short_design), "--out", str(tmp_path / "o"), "--tolerance", "0.1", "--quiet"], tmp_path
    )
    assert (tmp_path / "o" / "short_male.step").exists() and (tmp_path / "o" / "short_female.dxf").exists()
    # a rotor design imports none of the gear commands' modules (exports.svg pulled xml.sax,
    # urllib.request, http.client and ssl)
    assert "rotorcad.cli.gear" not in modules and "http.client" not in modules
    assert (worker is not None) == bool(worker_count())
    if worker is not None:
        assert heavy_in(modules) == set()
        assert "ezdxf" not in modules  # the DXF is written in the worker too
        # the worker, forked from the command (it holds what the command had imported), adds
        # OpenCASCADE and ezdxf for the STEP and DXF files and nothing else heavy
        assert heavy_in(worker) == {"OCP"} and "ezdxf" in worker and "rotorcad.cli.gear" not in worker
    else:
        assert "ezdxf" in modules and any(m.startswith("OCP") for m in modules)


def test_3mf_still_uses_trimesh(short_design, tmp_path):
    modules = loaded_modules(
        ["export", str(short_design), "--format", "3mf", "--tolerance", "0.1", "--out", str(tmp_path / "o")], tmp_path
    )
    assert (tmp_path / "o" / "short_male.3mf").exists() and "trimesh" in modules


def test_gear_json_imports_no_scipy_solver_or_plotting(tmp_path):
    modules = loaded_modules(["gear", "--teeth", "20", "--module", "2", "--json"], tmp_path)
    assert heavy_in(modules) == set()
    assert "rich.progress" not in modules


def test_rotor_json_imports_no_scipy_solver_mesh_step_or_plotting_library(tmp_path):
    modules = loaded_modules(["rotor", str(SAMPLE), "--json"], tmp_path)
    # the meshline's tangents come from rotorcad.spline_slopes, not scipy.interpolate
    assert heavy_in(modules) == set()
