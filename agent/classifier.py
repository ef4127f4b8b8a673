"""The no-LLM router: a shipped linear classifier over example questions, masked by what the task ran.

The weights come from scripts/train_router.py (TF-IDF over words and character n-grams, then multinomial
logistic regression, fitted with scikit-learn) and are scored here in plain Python, so a question costs
microseconds and a cold start imports neither scikit-learn nor SciPy, and fits nothing.
"""

from __future__ import annotations

import json
import math
import re
from collections import Counter
from collections.abc import Iterable
from functools import cache
from importlib import resources
from typing import Any

GENERIC = "generic"
MODEL_FILE = "data/router_model.json"
# scikit-learn's default token pattern and whitespace normalisation, which the weights were fitted with.
_TOKEN = re.compile(r"(?u)\b\w\w+\b")
_SPACE = re.compile(r"\s\s+")


def examples() -> dict[str, list[str]]:
    from hexar.fastyaml import load

    text = resources.files("hexar.agent").joinpath("data/router_examples.yaml").read_text(encoding="utf-8")
    data: dict[str, list[str]] = load(text)
    return data


def word_ngrams(text: str, lo: int, hi: int) -> list[str]:
    tokens = _TOKEN.findall(text)
    grams: list[str] = []
    for n in range(lo, hi + 1):
        grams.extend(" ".join(tokens[i:i + n]) for i in range(len(tokens) - n + 1))
    return grams


def char_wb_ngrams(text: str, lo: int, hi: int) -> list[str]:
    """Character n-grams inside word boundaries, padded with a space; a short word counts once."""
    grams: list[str] = []
    for word in _SPACE.sub(" ", text).split():
        w = f" {word} "
        for n in range(lo, hi + 1):
            grams.extend(w[i:i + n] for i in range(max(1, len(w) - n + 1)))
            if len(w) <= n:
                break
    return grams


class QuestionClassifier:
    """Scores a question against every label: softmax of a linear model over L2-normalised sublinear TF-IDF."""

    def __init__(self, model: dict[str, Any] | None = None) -> None:
        model = model or _load()
        self.labels: list[str] = list(model["labels"])
        self._intercept: list[float] = list(model["intercept"])
        self._blocks = [(char_wb_ngrams if name == "chars" else word_ngrams, tuple(model[name]["ngram_range"]),
                         model[name]["terms"]) for name in ("words", "chars")]

    def scores(self, question: str) -> dict[str, float]:
        text = question.lower()
        logits = list(self._intercept)
        for grams_of, (lo, hi), terms in self._blocks:
            counts = Counter(g for g in grams_of(text, lo, hi) if g in terms)
            values = {g: (1.0 + math.log(n)) * terms[g][0] for g, n in counts.items()}
            norm = math.sqrt(sum(v * v for v in values.values()))
            if norm == 0.0:
                continue
            for g, v in values.items():
                weights = terms[g]
                for k in range(len(logits)):
                    logits[k] += v / norm * weights[k + 1]
        top = max(logits)
        exps = [math.exp(x - top) for x in logits]
        total = sum(exps)
        return {label: e / total for label, e in zip(self.labels, exps, strict=True)}

    def choose(self, question: str, candidates: Iterable[str]) -> tuple[str, float]:
        """The most likely label among `candidates` (and `generic`), with its share of their mass."""
        scores = self.scores(question)
        allowed = [c for c in candidates if c in scores] + [GENERIC]
        masked = [scores[c] for c in allowed]
        best = max(range(len(masked)), key=masked.__getitem__)
        return allowed[best], masked[best] / sum(masked)


def _load() -> dict[str, Any]:
    data: dict[str, Any] = json.loads(resources.files("hexar.agent").joinpath(MODEL_FILE).read_text("utf-8"))
    return data


@cache
def default_classifier() -> QuestionClassifier:
    return QuestionClassifier()
