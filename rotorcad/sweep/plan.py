"""The plan of a design sweep: a base design and the parameters to vary, turned into variants.

A sweep file (TOML) reads::

    [sweep]
    base = "rack_involute_5_6.toml"   # a design file, relative to the sweep file (or a [base] table)
    method = "grid"                   # grid | random | latin-hypercube
    samples = 200                     # variants drawn by random / latin-hypercube
    seed = 1
    compute = ["hobbability", "interference", "volume", "clearance"]  # beside the pair and Rinder's analysis
    clearance = 0.05                  # mm: the normal clearance designed into the female for "clearance"

    [vary]                            # "table.key" of the design = values
    "pair.male_teeth" = [4, 5, 6]                          # a list
    "profile.lobe_width" = {from = 0.5, to = 0.7, step = 0.05}   # a range with a step (both ends in)
    "pair.lead" = {min = 200.0, max = 400.0}               # bounds: drawn (random, latin-hypercube)
    "profile.family" = ["rack-involute", "n-rack"]         # the family is an axis too

    [families.n-rack]                 # parameters of a family on the axis other than the base's
    driving_width = 1.2
    "pair.male_tip_radius" = "r1w + 1.39*m"   # and [pair] / [housing] values for that family

``grid`` takes every combination of the lists and ranges (bounds are refused there). ``random`` and
``latin-hypercube`` draw ``samples`` variants: bounds uniformly (integers when both bounds are
integers), lists and ranges as their values; Latin hypercube sampling stratifies every parameter
over its range (McKay, Beckman & Conover 1979: one sample in each of ``samples`` strata, the strata
matched across parameters by a random permutation each). A range whose end is off its step grid
ends at that end (the last step shorter), never short of it. The same file and seed give the same
variants in the same order.

The variants are never held all at once: :meth:`SweepPlan.iter_variants` yields them in blocks, so
planning a million variants costs the memory of a few thousand. What does have to fit is the results
table of the whole sweep (one row per variant): a plan whose table would need more than
:data:`MAX_TABLE_BYTES` is refused before any work, naming the largest count that fits.
"""

from __future__ import annotations

import hashlib
import itertools
import json
from collections.abc import Iterator
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

import numpy as np

from rotorcad.errors import DesignError

TABLES = ("pair", "profile", "housing", "operating")
MAX_VARIANTS = 10_000_000
BLOCK = 4096
"""Variants drawn at a time: the plan's memory does not grow with the number of variants."""

MAX_TABLE_BYTES = 2_000_000_000
"""Most memory the results table of one sweep may take (CONTRACT.md: a request that would need more
than about 2 GB is refused before it starts)."""

ROW_BYTES = 1_000
"""Memory of one row of the results table at its peak, bytes: a row takes 260-360 bytes in pandas
(measured on sweeps with and without hobbability and interference: 29-33 columns, the key, reason,
defect kinds and hob reason as Python strings), and the table is held about three times over while
the Parquet parts are joined, sorted and ranked."""


class Sampling(Enum):
    """How the variants are made from the varied parameters."""

    GRID = "grid"
    RANDOM = "random"
    LATIN_HYPERCUBE = "latin-hypercube"


class Extra(Enum):
    """Analyses a sweep may add to the pair and Rinder's analysis."""

    HOBBABILITY = "hobbability"
    INTERFERENCE = "interference"
    VOLUME = "volume"
    CLEARANCE = "clearance"


@dataclass(frozen=True)
class Parameter:
    """One varied design value.

    Attributes
    ----------
    name : str
        ``table.key`` of the design (e.g. ``pair.lead``).
    values : tuple, optional
        The values of a list or range.
    bounds : tuple[float, float], optional
        (min, max) of a drawn parameter.
    integer : bool
        Whether drawn values are whole numbers.
    """

    name: str
    values: tuple[Any, ...] | None = None
    bounds: tuple[float, float] | None = None
    integer: bool = False

    @property
    def continuous(self) -> bool:
        """Whether the parameter is drawn from real bounds (two draws never coincide)."""
        return self.bounds is not None and not self.integer

    def occurrences(self) -> tuple[int, ...]:
        """For each value of a list, how many equal values come before it in the list."""
        seen: dict[str, int] = {}
        out = []
        for v in self.values or ():
            text = json.dumps(_plain(v))
            seen[text] = seen.get(text, -1) + 1
            out.append(seen[text])
        return tuple(out)


@dataclass(frozen=True)
class Variant:
    """One design of a sweep: its number in the plan, its key and the values that differ from the base.

    Parameters
    ----------
    index : int
        Number of the variant in the plan, from 0.
    key : str
        Digest that identifies it across runs (:meth:`SweepPlan.variants`).
    values : dict
        ``table.key`` -> value of every varied parameter.
    """

    index: int
    key: str
    values: dict[str, Any]


@dataclass(frozen=True)
class SweepPlan:
    """A base design, the varied parameters and how to sample them.

    Parameters
    ----------
    base : dict
        The base design mapping (tables as a design file holds them).
    parameters : tuple of Parameter
        The varied design values.
    sampling : Sampling
        Grid, random or Latin hypercube.
    samples : int
        Variants drawn by random / Latin hypercube sampling (0 for a grid).
    seed : int
        Seed of the random numbers.
    extras : tuple of Extra
        Analyses added to the pair and Rinder's analysis.
    clearance : float, mm
        Normal clearance designed into the female for the "clearance" analysis.
    families : dict
        Family name -> the [profile] parameters of that family when the family is an axis
        (``[families.NAME]`` of the sweep file).
    """

    base: dict[str, Any]
    parameters: tuple[Parameter, ...]
    sampling: Sampling = Sampling.GRID
    samples: int = 0
    seed: int = 0
    extras: tuple[Extra, ...] = ()
    clearance: float = 0.05  # mm, designed normal clearance of the "clearance" analysis
    families: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def signature(self) -> str:
        """A digest (hex) of what every variant shares: the base design, the extra analyses and the designed clearance.

        A variant's key holds it, so that results of a changed base are never taken for this plan's.
        """
        shared = [self.base, sorted(e.value for e in self.extras), self.clearance]
        if self.families:
            shared.append(self.families)
        return hashlib.sha1(json.dumps(shared, sort_keys=True, default=str).encode()).hexdigest()

    def variants(self) -> list[Variant]:
        """Return every variant in a list (for a small plan; a sweep reads :meth:`iter_variants`).

        Returns
        -------
        list of Variant
        """
        return list(self.iter_variants())

    def iter_variants(self) -> Iterator[Variant]:
        """Yield every variant in a fixed order (deterministic for the plan), a block at a time.

        A variant's key is a digest of :attr:`signature`, its values and which occurrence of these
        values it is: it stays the same when a list gets more values, so a resumed sweep computes
        only the new ones. For a grid the occurrence is that of each value in its list; drawn
        variants with a real-valued parameter never repeat (occurrence 0), drawn variants of
        whole numbers and list values only are told apart by their number in the plan.

        Yields
        ------
        Variant
        """
        names = [p.name for p in self.parameters]
        signature = self.signature
        if self.sampling is Sampling.GRID:
            counts = [p.occurrences() for p in self.parameters]
            rows = itertools.product(*(range(len(p.values)) for p in self.parameters))
            for i, picks in enumerate(rows):
                values = {n: _plain(p.values[k]) for n, p, k in zip(names, self.parameters, picks, strict=True)}
                occurrence = [c[k] for c, k in zip(counts, picks, strict=True)]
                tag = "0" if not any(occurrence) else ",".join(map(str, occurrence))
                yield Variant(i, _key(signature, values, tag), values)
            return
        unique = any(p.continuous for p in self.parameters)
        rng = np.random.default_rng(self.seed)  # the uniform stream, read block after block
        for start in range(0, self.samples, BLOCK):
            unit = self._unit(start, min(BLOCK, self.samples - start), rng)
            columns = [self._draw(p, u) for p, u in zip(self.parameters, unit.T, strict=True)]
            for j, row in enumerate(zip(*columns, strict=True)):
                i = start + j
                values = {n: _plain(v) for n, v in zip(names, row, strict=True)}
                yield Variant(i, _key(signature, values, "0" if unique else f"#{i}"), values)

    def _unit(self, start: int, count: int, rng: np.random.Generator) -> np.ndarray:
        """Draw numbers in [0, 1) of the variants ``start`` .. ``start + count - 1``: (count, parameters).

        Uniform: one stream of ``numpy.random.default_rng(seed)`` read block after block (the same
        numbers as one draw of all). Latin hypercube: for parameter j, variant i lies in stratum
        ``perm_j(i)`` of ``samples``, at a uniform place within it; ``perm_j`` is a keyed bijection of
        0 .. samples-1 (:func:`_permutation`), so no permutation array is held.
        """
        d = len(self.parameters)
        if self.sampling is Sampling.RANDOM:
            return rng.random((count, d))
        index = np.arange(start, start + count, dtype=np.uint64)
        jitter = np.random.default_rng([self.seed, start // BLOCK]).random((count, d))
        strata = np.column_stack([_permutation(index, self.samples, self.seed * 1_000_003 + j) for j in range(d)])
        return (strata + jitter) / self.samples

    @staticmethod
    def _draw(p: Parameter, u: np.ndarray) -> list[Any]:
        """Map numbers ``u`` in [0, 1) to values of parameter ``p``: one of its values, or within its bounds."""
        if p.values is not None:
            return [p.values[i] for i in np.minimum((u * len(p.values)).astype(int), len(p.values) - 1)]
        lo, hi = p.bounds
        if p.integer:
            return [int(v) for v in np.minimum(np.floor(lo + u * (hi - lo + 1)), hi)]
        return [float(v) for v in lo + u * (hi - lo)]

    @property
    def count(self) -> int:
        """Number of variants."""
        if self.sampling is Sampling.GRID:
            return int(np.prod([len(p.values) for p in self.parameters], dtype=object))
        return self.samples

    def design(self, variant: Variant) -> dict[str, Any]:
        """Return the design mapping of one variant (the base with its values, :func:`apply`)."""
        return apply(self.base, variant.values, self.families)


def _key(signature: str, values: dict[str, Any], tag: str) -> str:
    """Digest of a variant: the plan's signature, its values and its occurrence tag."""
    text = json.dumps(values, sort_keys=True)
    return hashlib.sha1(f"{signature}|{text}|{tag}".encode()).hexdigest()[:16]


def _permutation(index: np.ndarray, n: int, key: int) -> np.ndarray:
    """Map ``index`` (uint64 array of numbers below ``n``) through a keyed bijection of 0 .. n-1.

    A four-round Feistel network on the smallest even number of bits that holds ``n`` is a bijection
    of 0 .. 2^bits - 1; applied again to the values that land at or above ``n`` ("cycle walking",
    Black & Rogaway 2002) it is a bijection of 0 .. n-1. Vectorised; no table of n entries.
    """
    bits = max(2, int(np.ceil(np.log2(max(n, 2)))))
    bits += bits % 2
    half = np.uint64(bits // 2)
    mask = np.uint64((1 << (bits // 2)) - 1)
    round_keys = np.random.default_rng(key).integers(0, 2**31, 4, dtype=np.uint64)
    mult = np.uint64(0x9E3779B1)

    def feistel(x: np.ndarray) -> np.ndarray:
        left, right = x >> half, x & mask
        for k in round_keys:
            f = ((right * mult + k) ^ (right >> np.uint64(3))) & mask
            left, right = right, left ^ f
        return (left << half) | right

    y = feistel(index.astype(np.uint64))
    over = y >= n
    while over.any():
        y[over] = feistel(y[over])
        over = y >= n
    return y.astype(np.float64)


def _plain(value: Any) -> Any:
    """Turn numpy scalars into Python ones (for JSON and TOML)."""
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (np.floating,)):
        return float(value)
    return value


def _number(value: Any) -> bool:
    """Tell whether ``value`` is an int or a float (a bool is not)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _range_values(lo: Any, hi: Any, step: Any) -> tuple[Any, ...]:
    """List the values of a range: ``from``, ``from + step``, ... and ``to`` itself when it is off the step grid."""
    n = int(np.floor((hi - lo) / step * (1 + 1e-12))) + 1
    whole = all(isinstance(v, int) for v in (lo, hi, step))
    values = [int(lo + i * step) if whole else float(round(lo + i * step, 12)) for i in range(n)]
    if abs(values[-1] - hi) > 1e-9 * max(abs(step), abs(hi)):  # the end off the grid: kept, the last step shorter
        values.append(hi if whole else float(hi))
    return tuple(values)


def _parameter(name: str, spec: Any) -> Parameter:
    """Read a [vary] entry: a list, {from, to, step} or {min, max}; raises :class:`DesignError` naming it."""
    table, _, key = name.partition(".")
    if table not in TABLES or not key:
        raise DesignError(f"[vary] '{name}'", "a design value named table.key with a table of " + ", ".join(TABLES), None)
    if isinstance(spec, list):
        if not spec or len(spec) > 100_000:
            raise DesignError(f"[vary] '{name}'", "a list of 1 to 100000 values", len(spec))
        return Parameter(name, values=tuple(spec))
    if isinstance(spec, dict) and set(spec) == {"from", "to", "step"}:
        lo, hi, step = spec["from"], spec["to"], spec["step"]
        if not all(_number(v) and np.isfinite(v) for v in (lo, hi, step)) or not step > 0 or not hi >= lo:
            raise DesignError(f"[vary] '{name}'", "a range with from <= to and a positive step", spec)
        n = int(np.floor((hi - lo) / step * (1 + 1e-12))) + 1
        if n > 100_000:
            raise DesignError(f"[vary] '{name}'", "a range of at most 100000 values", n)
        return Parameter(name, values=_range_values(lo, hi, step))
    if isinstance(spec, dict) and set(spec) == {"min", "max"}:
        lo, hi = spec["min"], spec["max"]
        if not all(_number(v) and np.isfinite(v) for v in (lo, hi)) or not hi > lo:
            raise DesignError(f"[vary] '{name}'", "bounds with min < max", spec)
        return Parameter(name, bounds=(float(lo), float(hi)), integer=isinstance(lo, int) and isinstance(hi, int))
    raise DesignError(f"[vary] '{name}'", "a list, {from, to, step} or {min, max}", spec)


def _axis_families(parameters: tuple[Parameter, ...], base: dict[str, Any]) -> list[str]:
    """Return the families of the sweep: those of a ``profile.family`` axis, else the base design's."""
    for p in parameters:
        if p.name == "profile.family":
            return list(dict.fromkeys(p.values or ()))
    return [base.get("profile", {}).get("family")]


def _check_values(parameter: Parameter, base: dict[str, Any], families: list[str] | None = None) -> None:
    """Check that a varied key is a key of the design and every value is of the type the design takes there.

    For [profile] the key must be a parameter of every family of the sweep (the base's, or each one
    of a ``profile.family`` axis); ``profile.family`` takes family names. Refused with
    :class:`DesignError` before anything is computed, naming the [vary] entry.
    """
    from rotorcad.design import HOUSING_KEYS, OPERATING_KEYS, PAIR_KEYS
    from rotorcad.rotor_families import FAMILIES

    table, _, key = parameter.name.partition(".")
    label = f"[vary] '{parameter.name}'"
    families = families or [base.get("profile", {}).get("family")]
    if table == "profile" and key == "family":
        if parameter.values is None:
            raise DesignError(label, "a list of family names", parameter.bounds)
        for value in parameter.values:
            if value not in FAMILIES:
                raise DesignError(label, "a list of family names: " + ", ".join(sorted(FAMILIES)), repr(value))
        return
    if table == "profile":
        for family in families:
            schema = FAMILIES.get(family, (None, {}))[1]
            if key not in schema:
                allowed = ", ".join(sorted(schema)) or "none"
                raise DesignError(label, f"one of the {family} family's parameters: {allowed}", None, "unknown key")
        kind = (int, float)
    else:
        keys = {"pair": PAIR_KEYS, "housing": HOUSING_KEYS, "operating": OPERATING_KEYS}[table]
        if key not in keys:
            raise DesignError(label, f"a key of [{table}]: " + ", ".join(sorted(keys)), None, "unknown key")
        kind = keys[key]
    values = parameter.values if parameter.values is not None else parameter.bounds
    for value in values:
        if kind is str:
            ok = isinstance(value, str)
        elif kind is int:
            ok = isinstance(value, int) and not isinstance(value, bool)
        else:
            ok = _number(value) and bool(np.isfinite(value))
        if not ok:
            need = {str: "text", int: "whole numbers"}.get(kind, "finite numbers")
            raise DesignError(label, f"{need} for {parameter.name}", repr(value))
    if kind is int and parameter.bounds is not None and not parameter.integer:
        raise DesignError(label, f"whole-number bounds for {parameter.name}", parameter.bounds)


def _family_tables(data: dict[str, Any], families: list[str]) -> dict[str, dict[str, Any]]:
    """Read ``[families.NAME]``: the parameters of each family on the axis; refused naming the table."""
    from rotorcad.rotor_families import FAMILIES

    tables = data.get("families", {})
    if not isinstance(tables, dict):
        raise DesignError("[families]", "tables [families.NAME] of family parameters", repr(tables))
    out = {}
    for name, params in tables.items():
        if name not in families:
            raise DesignError(f"[families.{name}]", "a family of the sweep's profile.family axis: " + ", ".join(families), None)
        if not isinstance(params, dict):
            raise DesignError(f"[families.{name}]", "a table of the family's parameters", repr(params))
        schema = FAMILIES[name][1]
        for key, value in params.items():
            if "." in key:  # a design value of another table for this family: "pair.male_tip_radius"
                table, _, sub = key.partition(".")
                if table not in ("pair", "housing") or not sub:
                    raise DesignError(f"[families.{name}] '{key}'", "a family parameter, or pair.KEY / housing.KEY", None)
                if not isinstance(value, str):  # an expression is checked when the variant's design is
                    _check_values(Parameter(f"{table}.{sub}", values=(value,)), {}, [name])
                continue
            if key not in schema:
                allowed = f"one of the {name} family's parameters: " + ", ".join(sorted(schema))
                raise DesignError(f"[families.{name}] {key}", allowed, None)
            if not (_number(value) or isinstance(value, str)):
                raise DesignError(f"[families.{name}] {key}", "a number (or an expression)", repr(value))
        out[name] = dict(params)
    return out


def sweep_plan(data: dict[str, Any], base: dict[str, Any]) -> SweepPlan:
    """Make the plan of a sweep file's mapping, with its base design already read.

    Parameters
    ----------
    data : dict
        The sweep file as TOML holds it ([sweep], [vary], optional [families], [constraints],
        [objectives]: the last two are read by :mod:`rotorcad.sweep.ranking`).
    base : dict
        The base design mapping (its tables as a design file holds them).

    Returns
    -------
    SweepPlan

    Raises
    ------
    DesignError
        An unknown table or key, a bad method, analysis, seed, sample count or clearance, a [vary]
        entry that is not a design value of the right type, bounds with method grid, more than
        :data:`MAX_VARIANTS` variants, or a results table that would not fit in
        :data:`MAX_TABLE_BYTES`.
    """
    for table in data:
        if table not in ("sweep", "vary", "base", "families", "constraints", "objectives"):
            allowed = "one of [sweep], [vary], [base], [families], [constraints], [objectives] in a sweep file"
            raise DesignError(f"table [{table}]", allowed, None, "unknown table")
    sweep = data.get("sweep", {})
    known = {"base", "method", "samples", "seed", "compute", "clearance", "defects"}
    for key in sweep:
        if key not in known:
            raise DesignError(f"key '{key}' in [sweep]", "one of " + ", ".join(sorted(known)), None, "unknown key")
    try:
        sampling = Sampling(sweep.get("method", "grid"))
    except ValueError:
        raise DesignError("[sweep] method", "one of " + ", ".join(s.value for s in Sampling), sweep.get("method")) from None
    try:
        extras = tuple(Extra(x) for x in sweep.get("compute", []))
    except (ValueError, TypeError):
        raise DesignError("[sweep] compute", "a list of " + ", ".join(e.value for e in Extra), sweep.get("compute")) from None
    vary = data.get("vary", {})
    if not isinstance(vary, dict) or not vary:
        raise DesignError("[vary]", "at least one design value to vary", None, "missing table")
    parameters = tuple(_parameter(name, spec) for name, spec in vary.items())
    families = _axis_families(parameters, base)
    for parameter in parameters:
        _check_values(parameter, base, families)
    family_tables = _family_tables(data, families) if "families" in data else {}
    samples, seed = sweep.get("samples", 0), sweep.get("seed", 0)
    if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
        raise DesignError("[sweep] seed", "a whole number of at least 0", seed)
    if sampling is Sampling.GRID:
        drawn = [p.name for p in parameters if p.bounds is not None]
        if drawn:
            raise DesignError(
                f"[vary] '{drawn[0]}'", "a list or range for method grid (bounds need random or latin-hypercube)", None
            )
    elif not (isinstance(samples, int) and not isinstance(samples, bool) and 1 <= samples <= MAX_VARIANTS):
        raise DesignError("[sweep] samples", f"a whole number from 1 to {MAX_VARIANTS}", samples)
    if sampling is Sampling.GRID and "samples" in sweep:
        raise DesignError("[sweep] samples", "left out for method grid (it takes every combination)", samples)
    clearance = sweep.get("clearance", 0.05)
    if not (_number(clearance) and 0 <= clearance <= 1):
        raise DesignError("[sweep] clearance", "a normal clearance from 0 to 1 mm", clearance)
    plan = SweepPlan(base, parameters, sampling, int(samples), int(seed), extras, float(clearance), family_tables)
    if plan.count > MAX_VARIANTS:
        raise DesignError("[vary]", f"at most {MAX_VARIANTS} combinations for method grid", plan.count)
    fit = max_variants_in_memory()
    if plan.count > fit:
        what = "[sweep] samples" if sampling is not Sampling.GRID else "[vary]"
        raise DesignError(
            what,
            f"at most {fit} variants (their results table would need {plan.count * ROW_BYTES / 1e9:.2g} GB, "
            f"more than the {MAX_TABLE_BYTES / 1e9:g} GB a sweep may take)",
            plan.count,
        )
    return plan


def max_variants_in_memory() -> int:
    """Most variants whose results table fits in :data:`MAX_TABLE_BYTES` (at :data:`ROW_BYTES` a row)."""
    return MAX_TABLE_BYTES // ROW_BYTES


def apply(base: dict[str, Any], values: dict[str, Any], families: dict[str, dict[str, Any]] | None = None) -> dict[str, Any]:
    """Put a variant's values into the base design mapping.

    Parameters
    ----------
    base : dict
        The base design mapping (kept as it is).
    values : dict
        ``table.key`` -> value.
    families : dict, optional
        Family name -> its [profile] parameters (``[families.NAME]``), for a ``profile.family``
        value other than the base's: the [profile] table is then that family's parameters (the
        base's parameters that the family also has, then these; the family's defaults for the rest);
        keys ``pair.KEY`` / ``housing.KEY`` there set those design values for that family.
        Varied values come last.

    Returns
    -------
    dict
        A new mapping (each table copied).
    """
    out = {table: dict(content) if isinstance(content, dict) else content for table, content in base.items()}
    family = values.get("profile.family")
    if family is not None and family != out.get("profile", {}).get("family"):
        from rotorcad.rotor_families import FAMILIES

        schema = FAMILIES[family][1]
        kept = {k: v for k, v in out.get("profile", {}).items() if k in schema}
        out["profile"] = {"family": family, **kept}
    for key, value in (families or {}).get(family, {}).items():
        table, _, sub = key.rpartition(".")
        out.setdefault(table or "profile", {})[sub] = value
    for name, value in values.items():
        table, _, key = name.partition(".")
        out.setdefault(table, {})[key] = value
    return out
