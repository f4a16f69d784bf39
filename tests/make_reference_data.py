"""Write tests/reference_data: the brute-force results the tests use (tests/independent_pairs.stored).

Runs the test files that use them with ROTORCAD_WRITE_REFERENCES=1, so that every result they
compute and do not find stored is written: the brute-force cuts (``cut_rotor``,
``female_cut_by_male``, the N-rack cuts, the male a female's positions cut) and the brute-force closest approaches
(``closest_approach``, ``true_gap``, keyed by their points and their code, so that a change of the
clearance code under test that moves the points it reads, or an edit of the brute force, needs this
run again: the suite then warns "tests/reference_data has no ..." and computes them). With
``--prune`` the stored files that no test read in this run are deleted (tests/reference_data/.used
lists those read). Run from the repository: ``python tests/make_reference_data.py [--prune]``.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).resolve().parent
REFERENCE_DATA = TESTS / "reference_data"
USERS = (  # the files that use stored brute-force results
    "test_reference_data.py",
    "test_inverse_independent.py",
    "test_deflection.py",
    "test_n_rack_cut.py",
    "test_racks_from_points.py",
    "test_clearance_zones.py",
    "test_clearance_phase.py",
    "test_contact_ratio_invariance.py",
    "test_clearance_lands.py",
    "test_clearance_sparse.py",
    "test_clearance_conjugate.py",
    "test_mate_points.py",
)


def main(argv: list[str]) -> int:
    env = {**os.environ, "ROTORCAD_WRITE_REFERENCES": "1"}
    used = REFERENCE_DATA / ".used"
    used.unlink(missing_ok=True)
    files = [str(TESTS / name) for name in USERS]
    code = subprocess.run([sys.executable, "-m", "pytest", "-q", "-n", "0", *files], cwd=TESTS.parent, env=env).returncode
    if code == 0 and "--prune" in argv:
        keep = set(used.read_text().split()) if used.exists() else set()
        for path in sorted(REFERENCE_DATA.glob("*.npy")):
            if path.name not in keep:
                print(f"deleting {path.relative_to(TESTS.parent)} (no test read it)")
                path.unlink()
    used.unlink(missing_ok=True)
    return code


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
