"""Fit the no-LLM router with scikit-learn and export it as plain weights (agent/data/router_model.json).

Only `scripts/train_router.py` and the rebuild test import this module: at run time the router scores questions
from the exported weights (agent/classifier.py) and never imports scikit-learn nor fits anything.
"""

from __future__ import annotations

from typing import Any

from hexar.agent.classifier import MODEL_FILE, examples

# TF-IDF over words and character n-grams (robust to misheard words), then logistic regression.
WORD_NGRAMS = (1, 2)
CHAR_NGRAMS = (3, 5)
C = 8.0
MAX_ITER = 2000
# Twelve significant digits: the file is identical across BLAS builds whose last bits differ, and the scores
# stay within 1e-10 of the fitted pipeline's.
DIGITS = 12


def _r(x: float) -> float:
    return float(f"{x:.{DIGITS}g}")


def fit(data: dict[str, list[str]] | None = None) -> Any:
    """The fitted scikit-learn pipeline (the router as it was fitted at every start before it was shipped)."""
    from sklearn.feature_extraction.text import TfidfVectorizer
    from sklearn.linear_model import LogisticRegression
    from sklearn.pipeline import FeatureUnion, Pipeline

    data = data or examples()
    texts = [q for qs in data.values() for q in qs]
    labels = [label for label, qs in data.items() for _ in qs]
    pipeline = Pipeline([
        ("features", FeatureUnion([
            ("words", TfidfVectorizer(ngram_range=WORD_NGRAMS, sublinear_tf=True)),
            ("chars", TfidfVectorizer(analyzer="char_wb", ngram_range=CHAR_NGRAMS, sublinear_tf=True)),
        ])),
        ("model", LogisticRegression(C=C, max_iter=MAX_ITER)),
    ])
    pipeline.fit(texts, labels)
    return pipeline


def export(pipeline: Any) -> dict[str, Any]:
    """Per feature block: each term's idf and its weight for every label, in the pipeline's column order."""
    union = pipeline.named_steps["features"]
    model = pipeline.named_steps["model"]
    coef = model.coef_
    blocks: dict[str, Any] = {}
    offset = 0
    for name, vec in union.transformer_list:
        terms = sorted(vec.vocabulary_.items(), key=lambda kv: kv[1])
        blocks[name] = {
            "ngram_range": list(vec.ngram_range),
            "terms": {
                term: [_r(vec.idf_[col]), *(_r(coef[k, offset + col]) for k in range(coef.shape[0]))]
                for term, col in terms
            },
        }
        offset += len(terms)
    return {
        "format": "hexar-router-1",
        "labels": [str(c) for c in model.classes_],
        "intercept": [_r(x) for x in model.intercept_],
        "words": blocks["words"],
        "chars": blocks["chars"],
        "fitted": {"C": C, "max_iter": MAX_ITER, "examples": sum(len(v) for v in (examples()).values()),
                   "file": MODEL_FILE},
    }
