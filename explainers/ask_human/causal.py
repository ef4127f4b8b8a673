"""The causal model of the ask-human-for-help skill: a pgmpy Bayesian network whose structure follows the
state machine and whose CPDs are learned from simulated executions, and the counterfactual search over it
(after Love et al.: the smallest intervention on the failed transition's causes that makes success likely).
"""

from __future__ import annotations

import json
import logging
import warnings
from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from importlib import resources
from itertools import combinations, product
from pathlib import Path
from typing import Any

from hexar.explainers.ask_human.variables import NONE, STATES, VARIABLES, WORLD, value_gap

FORMAT = "hexar.ask_human.bn/1"
TRAINING_N = 3000
TRAINING_SEED = 11
EQUIVALENT_SAMPLE_SIZE = 1.0
SUCCESS_THRESHOLD = 0.5
MODEL_FILE = "model.json"
ANSWERS_KEPT = 65_536  # memoised queries: a few MB at most

# The state machine as a DAG: what each recorded value depends on, and which values decide each transition.
EDGES: tuple[tuple[str, str], ...] = (
    ("person_detected", "person_std_rms"),
    ("person_detected", "detection_stable"),
    ("person_std_rms", "detection_stable"),
    ("detection_stable", "person_distance"),
    ("person_detected", "detection_next"),
    ("detection_stable", "detection_next"),
    ("person_distance", "detection_next"),
    ("detection_next", "navigate_executed"),
    ("navigate_executed", "navigation_failure"),
    ("person_distance", "navigation_failure"),
    ("navigation_failure", "robot_nav_err"),
    ("person_std_rms", "robot_nav_err"),
    ("navigate_executed", "navigation_next"),
    ("navigation_failure", "navigation_next"),
    ("detection_next", "ask_executed"),
    ("navigation_next", "ask_executed"),
    ("ask_executed", "user_accepted"),
    ("robot_nav_err", "user_accepted"),
    ("ask_executed", "ask_next"),
    ("user_accepted", "ask_next"),
    ("ask_next", "confirm_executed"),
    ("confirm_executed", "user_confirmed"),
    ("confirm_executed", "confirmation_next"),
    ("user_confirmed", "confirmation_next"),
    ("detection_next", "outcome"),
    ("navigation_next", "outcome"),
    ("ask_next", "outcome"),
    ("confirmation_next", "outcome"),
)


def _quiet_pgmpy() -> None:
    # pgmpy announces deprecations and CPD replacements on every import and fit; none of it is
    # actionable here.
    warnings.filterwarnings("ignore", category=FutureWarning, module=r"pgmpy(\..*)?")
    logging.getLogger("pgmpy").setLevel(logging.ERROR)


def children(node: str) -> list[str]:
    return [b for a, b in EDGES if a == node]


def parents(node: str) -> list[str]:
    return [a for a, b in EDGES if b == node]


def _reach(nodes: Iterable[str], step: Callable[[str], list[str]]) -> set[str]:
    seen: set[str] = set()
    todo = list(nodes)
    while todo:
        for nxt in step(todo.pop()):
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return seen


def descendants(nodes: Iterable[str]) -> set[str]:
    return _reach(nodes, children)


def ancestors(node: str) -> set[str]:
    return _reach([node], parents)


def hops(src: str, dst: str) -> int:
    """Length of the shortest directed path src -> dst: how directly a variable drives a transition."""
    queue, seen = deque([(src, 0)]), {src}
    while queue:
        node, d = queue.popleft()
        if node == dst:
            return d
        for child in children(node):
            if child not in seen:
                seen.add(child)
                queue.append((child, d + 1))
    return len(VARIABLES)


@dataclass(frozen=True)
class Counterfactual:
    """do(changes) and what the model says then; `flips`: success becomes the most probable outcome."""

    changes: tuple[tuple[str, str, str], ...]  # (variable, observed value, value under the intervention)
    p_success: float
    flips: bool
    tried: int


class CausalModel:
    """A fitted network plus the intervention queries the explainer needs.

    pgmpy learns the CPDs (`fit`); queries run on the CPD tables with NumPy (exact variable elimination by
    einsum), so answering a question never imports pgmpy, pandas or scikit-learn (seconds at a cold start).
    """

    def __init__(self, network: Any, meta: Mapping[str, Any], specs: Mapping[str, Any] | None = None,
                 edges: Sequence[tuple[str, str]] = EDGES) -> None:
        self._network = network
        self.meta = dict(meta)
        self._edges = [tuple(e) for e in edges]
        self._specs: dict[str, Any] = dict(specs) if specs is not None else _cpd_specs(network)
        self._tables = _tables_of(self._specs)
        self._answers: dict[tuple[Any, ...], float] = {}

    @classmethod
    def fit(cls, rows: Sequence[Mapping[str, str]], **meta: Any) -> CausalModel:
        """Learn every CPD from executions (BDeu prior, so unseen parent combinations stay uniform)."""
        _quiet_pgmpy()
        import pandas as pd
        from pgmpy.models import DiscreteBayesianNetwork
        from pgmpy.parameter_estimator import DiscreteBayesianEstimator

        frame = pd.DataFrame([[row[v] for v in VARIABLES] for row in rows], columns=list(VARIABLES))
        network = DiscreteBayesianNetwork(list(EDGES))
        estimator = DiscreteBayesianEstimator(
            state_names={v: list(s) for v, s in STATES.items()},
            prior_type="BDeu",
            equivalent_sample_size=EQUIVALENT_SAMPLE_SIZE,
        )
        network.fit(frame, estimator=estimator)
        return cls(
            network, {"executions": len(rows), "equivalent_sample_size": EQUIVALENT_SAMPLE_SIZE, **meta}
        )

    def to_json(self) -> dict[str, Any]:
        return {"format": FORMAT, "meta": self.meta, "edges": [list(e) for e in EDGES], "cpds": self._specs}

    def save(self, path: Path) -> None:
        path.write_text(json.dumps(self.to_json(), indent=1, sort_keys=True) + "\n", encoding="utf-8")

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> CausalModel:
        if data.get("format") != FORMAT:
            raise ValueError(f"not an ask-human causal model (format {data.get('format')!r})")
        return cls(None, data.get("meta", {}), data["cpds"], [(a, b) for a, b in data["edges"]])

    @property
    def network(self) -> Any:
        """The pgmpy network (built from the tables on first use: only training and its checks need it)."""
        if self._network is None:
            _quiet_pgmpy()
            from pgmpy.factors.discrete import TabularCPD
            from pgmpy.models import DiscreteBayesianNetwork

            network = DiscreteBayesianNetwork(self._edges)
            for var, spec in self._specs.items():
                names = spec["state_names"]
                network.add_cpds(
                    TabularCPD(
                        var,
                        len(names[var]),
                        spec["values"],
                        evidence=spec["evidence"] or None,
                        evidence_card=[len(names[e]) for e in spec["evidence"]] or None,
                        state_names=names,
                    )
                )
            self._network = network
        return self._network

    @classmethod
    def load(cls, path: Path | None = None) -> CausalModel:
        """The model shipped with the package, or the one at `path`."""
        if path is None:
            text = (
                resources.files("hexar.explainers.ask_human").joinpath(MODEL_FILE).read_text(encoding="utf-8")
            )
        else:
            text = Path(path).read_text(encoding="utf-8")
        return cls.from_json(json.loads(text))

    def cpd_values(self, var: str) -> list[list[float]]:
        table = self._tables[var]
        return [[float(x) for x in row] for row in table.values.reshape(table.values.shape[0], -1)]

    def probability(
        self, var: str, value: str, do: Mapping[str, str], evidence: Mapping[str, str] | None = None
    ) -> float:
        """P(var = value | do(do), evidence), computed once per query: the tables never change, and a fleet asks
        the same few queries of thousands of recordings (planning the sum takes longer than computing it)."""
        key = (var, value, tuple(sorted(do.items())), tuple(sorted((evidence or {}).items())))
        answer = self._answers.get(key)
        if answer is None:
            if len(self._answers) >= ANSWERS_KEPT:
                self._answers.clear()
            answer = self._answers[key] = self._probability(var, value, do, evidence)
        return answer

    def _probability(self, var: str, value: str, do: Mapping[str, str], evidence: Mapping[str, str] | None) -> float:
        import numpy as np

        known = {**(evidence or {}), **do}
        if var in known:
            return 1.0 if known[var] == value else 0.0
        # do(): the intervened variables lose their parents (the mutilated network), then everything is
        # conditioned on; an intervened root's own table is then a constant that normalisation removes.
        label = {v: i for i, v in enumerate(VARIABLES)}
        operands: list[Any] = []
        for child, table in self._tables.items():
            if child in do:
                continue
            index = tuple(table.names[a].index(known[a]) if a in known else slice(None) for a in table.axes)
            operands += [table.values[index], [label[a] for a in table.axes if a not in known]]
        marginal = np.einsum(*operands, [label[var]], optimize="greedy")
        total = float(marginal.sum())
        return float(marginal[self._tables[var].names[var].index(value)] / total) if total > 0 else 0.0

    def p_success(self, do: Mapping[str, str], evidence: Mapping[str, str] | None = None) -> float:
        return self.probability("outcome", "success", do, evidence)


@dataclass(frozen=True)
class _Table:
    """One CPD as an array with an axis per variable: the child first, then its parents."""

    axes: tuple[str, ...]
    names: dict[str, list[str]]
    values: Any


def _cpd_specs(network: Any) -> dict[str, dict[str, Any]]:
    cpds = {}
    for var in VARIABLES:
        cpd = network.get_cpds(var)
        evidence = list(cpd.variables[1:])
        cpds[var] = {
            "evidence": evidence,
            "state_names": {v: list(cpd.state_names[v]) for v in [var, *evidence]},
            "values": [[round(float(x), 10) for x in row] for row in cpd.get_values()],
        }
    return cpds


def _tables_of(cpds: Mapping[str, Mapping[str, Any]]) -> dict[str, _Table]:
    import numpy as np

    tables = {}
    for var, spec in cpds.items():
        names = {k: list(v) for k, v in spec["state_names"].items()}
        axes = (var, *spec["evidence"])
        values = np.asarray(spec["values"], dtype=np.float64).reshape([len(names[a]) for a in axes])
        tables[var] = _Table(axes, names, values)
    return tables


def _kept_evidence(observed: Mapping[str, str], intervened: Iterable[str]) -> dict[str, str]:
    """What stays as it was under the intervention: every observed value that is not downstream of it."""
    changed = set(intervened)
    downstream = descendants(changed) | changed
    return {k: v for k, v in observed.items() if k not in downstream}


def search_counterfactual(
    model: CausalModel,
    observed: Mapping[str, str],
    failed_transition: str,
    *,
    threshold: float = SUCCESS_THRESHOLD,
    max_size: int = 2,
) -> Counterfactual | None:
    """The smallest intervention on the failed transition's observable causes under which the model makes
    success the most probable outcome; the most probable one found if none does.

    Among interventions of the same size, the one closest to the transition in the graph wins, then the one
    that changes the values least (the nearest possible world), then the most probable success.
    """
    candidates = sorted(
        (v for v in ancestors(failed_transition) if v in WORLD and observed.get(v, NONE) != NONE),
        key=lambda v: (hops(v, failed_transition), VARIABLES.index(v)),
    )
    best: tuple[tuple[float, float, float], Counterfactual] | None = None
    tried = 0
    for size in range(1, max_size + 1):
        passing: list[tuple[tuple[float, float, float], Counterfactual]] = []
        for group in combinations(candidates, size):
            options = [[s for s in STATES[v] if s not in (NONE, observed[v])] for v in group]
            for values in product(*options):
                do = dict(zip(group, values, strict=True))
                p = model.p_success(do, _kept_evidence(observed, group))
                tried += 1
                changes = tuple((v, observed[v], do[v]) for v in group)
                rank = (
                    float(sum(hops(v, failed_transition) for v in group)),
                    float(sum(value_gap(v, observed[v], do[v]) for v in group)),
                    -p,
                )
                found = Counterfactual(changes, p, p > threshold, 0)
                if p > threshold:
                    passing.append((rank, found))
                if best is None or p > best[1].p_success:
                    best = (rank, found)
        if passing:
            rank, found = min(passing, key=lambda item: item[0])
            return Counterfactual(found.changes, found.p_success, True, tried)
    if best is None:
        return None
    return Counterfactual(best[1].changes, best[1].p_success, False, tried)
