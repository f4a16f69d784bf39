"""Write tests/reference_data: the brute-force cuts the tests use (tests/independent_pairs.stored).

Runs the test files that use them with ROTORCAD_WRITE_REFERENCES=1, so that every result they
compute and do not find stored is written (tests/independent_pairs.stored); delete the folder
first to write them all again. Run from the repository: ``python tests/make_reference_data.py``.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).resolve().parent
USERS = (  # the files that use stored cuts
    "test_inverse_independent.py",
    "test_deflection.py",
    "test_n_rack_cut.py",
    "test_racks_from_points.py",
    "test_clearance_zones.py",
)


def main() -> int:
    env = {**os.environ, "ROTORCAD_WRITE_REFERENCES": "1"}
    files = [str(TESTS / name) for name in USERS]
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-n", "0", *files], cwd=TESTS.parent, env=env).returncode


if __name__ == "__main__":
    raise SystemExit(main())
