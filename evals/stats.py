"""Significance tests of the paper (section V-E): Cochran's Q across the methods, then pairwise McNemar tests with
Holm correction, per metric and per robot module.

Outcomes are paired: the same cases, one binary outcome per case and method. McNemar uses the exact binomial
test on the discordant pairs (statsmodels' default), which suits the small discordant counts of 180 cases.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass
from itertools import combinations
from typing import Any

import numpy as np
from statsmodels.stats.contingency_tables import cochrans_q, mcnemar
from statsmodels.stats.multitest import multipletests


@dataclass(frozen=True)
class Pair:
    a: str
    b: str
    only_a: int  # cases where a's outcome is 1 and b's is 0
    only_b: int
    p: float
    p_holm: float

    @property
    def mark(self) -> str:
        return significance_mark(self.p_holm)


@dataclass(frozen=True)
class Comparison:
    """Cochran's Q over all methods (None with fewer than two) and the Holm-corrected pairwise tests."""

    methods: tuple[str, ...]
    n: int
    q: float | None
    df: int
    p: float | None
    pairs: tuple[Pair, ...]

    def as_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["pairs"] = [{**asdict(p), "mark": p.mark} for p in self.pairs]
        return d


def significance_mark(p: float) -> str:
    """As in the paper's figures: * p<0.05, ** p<0.01, *** p<0.001."""
    if p < 0.001:
        return "***"
    if p < 0.01:
        return "**"
    if p < 0.05:
        return "*"
    return ""


def cochran(table: np.ndarray[Any, Any]) -> tuple[float, float]:
    """Q and p for a cases x methods 0/1 table; no disagreement at all gives Q = 0, p = 1."""
    if table.shape[0] == 0 or np.all(table == table[:, :1]):
        return 0.0, 1.0
    res = cochrans_q(table)
    return float(res.statistic), float(res.pvalue)


def mcnemar_pair(a: Sequence[bool], b: Sequence[bool], exact: bool = True) -> tuple[int, int, float]:
    """Discordant counts and the McNemar p-value of two paired outcome lists."""
    x = np.asarray(a, dtype=bool)
    y = np.asarray(b, dtype=bool)
    table = [[int(np.sum(x & y)), int(np.sum(x & ~y))], [int(np.sum(~x & y)), int(np.sum(~x & ~y))]]
    only_a, only_b = table[0][1], table[1][0]
    if only_a + only_b == 0:
        return only_a, only_b, 1.0
    res = mcnemar(table, exact=exact)
    return only_a, only_b, float(res.pvalue)


def compare(outcomes: Mapping[str, Sequence[bool]]) -> Comparison | None:
    """The tests over paired outcomes by method; None when fewer than two methods have outcomes."""
    methods = tuple(m for m, v in outcomes.items() if v is not None)
    if len(methods) < 2:
        return None
    n = len(outcomes[methods[0]])
    if any(len(outcomes[m]) != n for m in methods):
        raise ValueError("outcomes must be paired: every method needs one outcome per case")
    table = np.array([[int(bool(outcomes[m][i])) for m in methods] for i in range(n)], dtype=int)
    q, p = cochran(table)
    raw = [(a, b, *mcnemar_pair(outcomes[a], outcomes[b])) for a, b in combinations(methods, 2)]
    adjusted = multipletests([r[4] for r in raw], method="holm")[1]
    pairs = tuple(Pair(a, b, oa, ob, p_raw, float(min(1.0, padj)))
                  for (a, b, oa, ob, p_raw), padj in zip(raw, adjusted, strict=True))
    return Comparison(methods, n, q, len(methods) - 1, p, pairs)


def mean_sd(values: Sequence[float]) -> tuple[float, float]:
    """Mean and population standard deviation (what the paper reports as sigma)."""
    if not values:
        return math.nan, math.nan
    arr = np.asarray(values, dtype=float)
    return float(arr.mean()), float(arr.std())
