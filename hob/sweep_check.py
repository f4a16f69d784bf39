"""The hobbability verdict of a sweep's variant (``[sweep] compute = ["hobbability"]``).

The sweep runs in the core (:mod:`rotorcad.sweep`), which does not import ``hob``: this module
registers :data:`ANALYSES` with the core's extension points when imported (:mod:`rotorcad.extensions`;
the entry point ``hob`` of ``rotorcad.extensions`` imports it for a script), and the command line
passes them explicitly. The verdict is that of ``rotorcad hob`` with its default
limits, for both rotors, judged through their racks (Rinder sec. 2.1).
"""

from __future__ import annotations

from typing import Any

from hob.rack import rotor_rack
from hob.verdict import HobLimits, judge
from rotorcad.extensions import register_sweep_analysis
from rotorcad.roles import Side
from rotorcad.sweep.plan import Extra


def hobbability(rotors: Any, spec: Any, clearance: float) -> dict[str, Any]:
    """Judge whether a hob can make both rotors of a variant.

    Parameters
    ----------
    rotors : ScrewRotors
        The variant's pair.
    spec : PairSpec
        Its spec (unused: the verdict needs the pair alone).
    clearance : float, mm
        The sweep's designed clearance (unused).

    Returns
    -------
    dict
        ``hobbable`` (bool) and ``hob_reason`` (the reasons against, "rotor: reason; ...").
    """
    verdicts = [judge(rotor_rack(rotors, side), HobLimits()) for side in Side]
    reasons = [f"{side}: {r}" for side, v in zip(Side, verdicts, strict=True) for r in v.reasons]
    return {"hobbable": all(v.hobbable for v in verdicts), "hob_reason": "; ".join(reasons)}


ANALYSES = {Extra.HOBBABILITY: hobbability}
"""The sweep analyses of this package, for :func:`rotorcad.sweep.run.run_sweep`'s ``analyses``."""

for _extra, _analysis in ANALYSES.items():  # the core finds the verdict without importing hob (rotorcad.extensions)
    register_sweep_analysis(_extra, _analysis)
