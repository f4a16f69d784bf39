"""Cutting tools, rack and hob-profile derivation, hobbability and cutting simulation.

:mod:`hob.tools` (trapezoidal hob, rack tool by points), :mod:`hob.rack` (the rack of a gear or
of a rotor pair), :mod:`hob.verdict` (hobbability judged through the rack, Rinder sec. 2.1),
:mod:`hob.cutting` (generating-cutting simulation by polygon booleans), :mod:`hob.undercut`
(Kollek & Osiński eq. 1 and the limit shifts), :mod:`hob.nomogram` (their Fig. 4) and
:mod:`hob.plotting`.
"""
