"""The statistics against published worked examples."""

from __future__ import annotations

import numpy as np
import pytest
from statsmodels.stats.contingency_tables import mcnemar

from hexar.evals.stats import cochran, compare, mcnemar_pair, mean_sd, significance_mark

# WaveMetrics Igor Pro manual, StatsCochranTest (5 groups x 9 blocks): Q = 5.56522, p = 0.234056 for wave1 and
# Q = 10.3636, p = 0.0347281 for wave2.
WAVE1 = [[0, 0, 0, 0, 1], [0, 0, 0, 0, 1], [0, 0, 0, 1, 1], [0, 1, 0, 1, 1], [0, 1, 0, 1, 0], [1, 1, 0, 1, 0],
         [1, 1, 0, 0, 0], [1, 0, 0, 0, 0], [1, 0, 0, 0, 0]]
WAVE2 = [[0, 0, 0, 0, 1], [0, 0, 0, 0, 1], [0, 0, 0, 1, 1], [0, 1, 0, 1, 1], [1, 1, 0, 1, 1], [1, 1, 0, 1, 1],
         [1, 1, 0, 1, 0], [1, 1, 0, 0, 0], [1, 0, 0, 0, 0]]


@pytest.mark.parametrize(("table", "q", "p"), [(WAVE1, 5.56522, 0.234056), (WAVE2, 10.3636, 0.0347281)])
def test_cochran_q_worked_examples(table: list[list[int]], q: float, p: float) -> None:
    got_q, got_p = cochran(np.array(table))
    assert got_q == pytest.approx(q, abs=1e-4)
    assert got_p == pytest.approx(p, abs=1e-6)


def test_mcnemar_textbook_example() -> None:
    # Agresti, Categorical Data Analysis: approval of the Prime Minister in two surveys, 1600 people,
    # (794, 150 / 86, 570): McNemar z^2 = (150 - 86)^2 / (150 + 86) = 17.36.
    res = mcnemar([[794, 150], [86, 570]], exact=False, correction=False)
    assert res.statistic == pytest.approx(17.356, abs=1e-3)
    a = [True] * 794 + [True] * 150 + [False] * 86 + [False] * 570
    b = [True] * 794 + [False] * 150 + [True] * 86 + [False] * 570
    only_a, only_b, p = mcnemar_pair(a, b, exact=False)
    assert (only_a, only_b) == (150, 86)
    assert p == pytest.approx(mcnemar([[794, 150], [86, 570]], exact=False).pvalue)  # continuity-corrected
    assert p < 0.001 and res.pvalue == pytest.approx(3.1e-5, rel=0.01)


def test_two_methods_q_equals_uncorrected_mcnemar() -> None:
    a = [1, 1, 1, 1, 1, 0, 1, 0, 1, 1]
    b = [0, 0, 1, 0, 1, 0, 0, 0, 1, 1]
    q, _ = cochran(np.array([a, b]).T)
    assert q == pytest.approx((4 - 0) ** 2 / (4 + 0))


def test_compare_applies_holm() -> None:
    n = 60
    hexar = [True] * n
    e2e = [i % 3 != 0 for i in range(n)]
    allc = [i % 10 != 0 for i in range(n)]
    res = compare({"hexar": hexar, "end-to-end": e2e, "all-components": allc})
    assert res is not None and res.df == 2 and res.p is not None and res.p < 0.001
    raw = sorted(p.p for p in res.pairs)
    holm = sorted(p.p_holm for p in res.pairs)
    assert holm[0] == pytest.approx(min(1.0, raw[0] * 3))
    assert all(h >= r for h, r in zip(holm, raw, strict=True))
    first = next(p for p in res.pairs if p.b == "end-to-end")
    assert (first.only_a, first.only_b) == (20, 0) and first.mark == "***"


def test_no_test_for_one_method_and_no_disagreement() -> None:
    assert compare({"hexar": [True, False]}) is None
    res = compare({"a": [True, False], "b": [True, False]})
    assert res is not None and res.q == 0.0 and res.p == 1.0 and res.pairs[0].p_holm == 1.0


def test_marks_and_sd() -> None:
    assert [significance_mark(p) for p in (0.2, 0.04, 0.009, 0.0009)] == ["", "*", "**", "***"]
    mean, sd = mean_sd([1.0] * 175 + [0.0] * 5)
    assert mean == pytest.approx(0.9722, abs=1e-4) and sd == pytest.approx(0.16, abs=0.005)  # the paper's sigma
