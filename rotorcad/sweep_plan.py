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

``grid`` takes every combination of the lists and ranges (bounds are refused there). ``random`` and
``latin-hypercube`` draw ``samples`` variants: bounds uniformly (integers when both bounds are
integers), lists and ranges as their values; Latin hypercube sampling (scipy.stats.qmc) stratifies
every parameter over its range. The same file and seed give the same variants in the same order.
"""

from __future__ import annotations

import hashlib
import itertools
import json
from dataclasses import dataclass
from enum import Enum
from typing import Any

import numpy as np

from rotorcad.errors import DesignError

TABLES = ("pair", "profile", "housing", "operating")
MAX_VARIANTS = 10_000_000


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
    """

    base: dict[str, Any]
    parameters: tuple[Parameter, ...]
    sampling: Sampling = Sampling.GRID
    samples: int = 0
    seed: int = 0
    extras: tuple[Extra, ...] = ()
    clearance: float = 0.05  # mm, designed normal clearance of the "clearance" analysis

    @property
    def signature(self) -> str:
        """A digest (hex) of what every variant shares: the base design, the extra analyses and the designed clearance.

        A variant's key holds it, so that results of a changed base are never taken for this plan's.
        """
        shared = [self.base, sorted(e.value for e in self.extras), self.clearance]
        return hashlib.sha1(json.dumps(shared, sort_keys=True, default=str).encode()).hexdigest()

    def variants(self) -> list[Variant]:
        """Every variant in a fixed order (deterministic for the plan).

        A variant's key is a digest of :attr:`signature`, its values and how many earlier variants
        have the same values: it stays the same when a list gets more values, so a resumed sweep
        computes only the new ones.
        """
        names = [p.name for p in self.parameters]
        if self.sampling is Sampling.GRID:
            rows = itertools.product(*(p.values for p in self.parameters))
        else:
            rows = zip(*(self._draw(p, u) for p, u in zip(self.parameters, self._unit().T, strict=True)), strict=True)
        out = []
        seen: dict[str, int] = {}
        signature = self.signature
        for i, row in enumerate(rows):
            values = {n: _plain(v) for n, v in zip(names, row, strict=True)}
            text = json.dumps(values, sort_keys=True)
            seen[text] = seen.get(text, -1) + 1
            digest = hashlib.sha1(f"{signature}|{text}|{seen[text]}".encode()).hexdigest()[:16]
            out.append(Variant(i, digest, values))
        return out

    def _unit(self) -> np.ndarray:
        """Draw (samples, parameters) numbers in [0, 1): uniform or Latin hypercube."""
        d = len(self.parameters)
        if self.sampling is Sampling.LATIN_HYPERCUBE:
            from scipy.stats import qmc

            return qmc.LatinHypercube(d=d, seed=self.seed).random(self.samples)
        return np.random.default_rng(self.seed).random((self.samples, d))

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
            return int(np.prod([len(p.values) for p in self.parameters]))
        return self.samples


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
        whole = all(isinstance(v, int) for v in (lo, hi, step))
        values = tuple(int(lo + i * step) if whole else float(round(lo + i * step, 12)) for i in range(n))
        return Parameter(name, values=values)
    if isinstance(spec, dict) and set(spec) == {"min", "max"}:
        lo, hi = spec["min"], spec["max"]
        if not all(_number(v) and np.isfinite(v) for v in (lo, hi)) or not hi > lo:
            raise DesignError(f"[vary] '{name}'", "bounds with min < max", spec)
        return Parameter(name, bounds=(float(lo), float(hi)), integer=isinstance(lo, int) and isinstance(hi, int))
    raise DesignError(f"[vary] '{name}'", "a list, {from, to, step} or {min, max}", spec)


def _check_values(parameter: Parameter, base: dict[str, Any]) -> None:
    """Check that a varied key is a key of the design and every value is of the type the design takes there.

    For [profile] the key must be one of the base family's parameters. Refused with
    :class:`DesignError` before anything is computed, naming the [vary] entry.
    """
    from rotorcad.design import HOUSING_KEYS, OPERATING_KEYS, PAIR_KEYS
    from rotorcad.rotor_families import FAMILIES

    table, _, key = parameter.name.partition(".")
    label = f"[vary] '{parameter.name}'"
    if table == "profile":
        family = base.get("profile", {}).get("family")
        if key == "family":
            raise DesignError(label, "a profile parameter (the family is the base design's)", None)
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


def sweep_plan(data: dict[str, Any], base: dict[str, Any]) -> SweepPlan:
    """Make the plan of a sweep file's mapping, with its base design already read.

    Parameters
    ----------
    data : dict
        The sweep file as TOML holds it ([sweep], [vary]).
    base : dict
        The base design mapping (its tables as a design file holds them).

    Returns
    -------
    SweepPlan

    Raises
    ------
    DesignError
        An unknown table or key, a bad method, analysis, seed, sample count or clearance, a [vary]
        entry that is not a design value of the right type, bounds with method grid, or more than
        :data:`MAX_VARIANTS` variants.
    """
    for table in data:
        if table not in ("sweep", "vary", "base"):
            raise DesignError(f"table [{table}]", "one of [sweep], [vary], [base] in a sweep file", None, "unknown table")
    sweep = data.get("sweep", {})
    known = {"base", "method", "samples", "seed", "compute", "clearance"}
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
    for parameter in parameters:
        _check_values(parameter, base)
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
    plan = SweepPlan(base, parameters, sampling, int(samples), int(seed), extras, float(clearance))
    if plan.count > MAX_VARIANTS:
        raise DesignError("[vary]", f"at most {MAX_VARIANTS} combinations for method grid", plan.count)
    return plan


def apply(base: dict[str, Any], values: dict[str, Any]) -> dict[str, Any]:
    """Put a variant's values into the base design mapping.

    Parameters
    ----------
    base : dict
        The base design mapping (kept as it is).
    values : dict
        ``table.key`` -> value.

    Returns
    -------
    dict
        A new mapping (each table copied).
    """
    out = {table: dict(content) if isinstance(content, dict) else content for table, content in base.items()}
    for name, value in values.items():
        table, _, key = name.partition(".")
        out.setdefault(table, {})[key] = value
    return out
