"""The no-LLM router: a scikit-learn classifier over example questions, masked by what the task ran."""

from __future__ import annotations

from collections.abc import Iterable
from functools import cache
from importlib import resources

import numpy as np
import yaml
from sklearn.feature_extraction.text import TfidfVectorizer
from sklearn.linear_model import LogisticRegression
from sklearn.pipeline import FeatureUnion, Pipeline

GENERIC = "generic"


def examples() -> dict[str, list[str]]:
    text = resources.files("hexar.agent").joinpath("data/router_examples.yaml").read_text(encoding="utf-8")
    data: dict[str, list[str]] = yaml.safe_load(text)
    return data


class QuestionClassifier:
    """TF-IDF over words and character n-grams (robust to misheard words), then logistic regression."""

    def __init__(self, data: dict[str, list[str]] | None = None) -> None:
        data = data or examples()
        texts = [q for qs in data.values() for q in qs]
        labels = [label for label, qs in data.items() for _ in qs]
        self.pipeline = Pipeline([
            ("features", FeatureUnion([
                ("words", TfidfVectorizer(ngram_range=(1, 2), sublinear_tf=True)),
                ("chars", TfidfVectorizer(analyzer="char_wb", ngram_range=(3, 5), sublinear_tf=True)),
            ])),
            ("model", LogisticRegression(C=8.0, max_iter=2000)),
        ])
        self.pipeline.fit(texts, labels)
        self.labels: list[str] = [str(c) for c in self.pipeline.classes_]

    def scores(self, question: str) -> dict[str, float]:
        probs = self.pipeline.predict_proba([question.lower()])[0]
        return {label: float(p) for label, p in zip(self.labels, probs, strict=True)}

    def choose(self, question: str, candidates: Iterable[str]) -> tuple[str, float]:
        """The most likely label among `candidates` (and `generic`), with its share of their mass."""
        scores = self.scores(question)
        allowed = [c for c in candidates if c in scores] + [GENERIC]
        masked = np.array([scores[c] for c in allowed])
        best = int(masked.argmax())
        return allowed[best], float(masked[best] / masked.sum())


@cache
def default_classifier() -> QuestionClassifier:
    return QuestionClassifier()
