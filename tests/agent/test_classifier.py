"""The router's shipped weights: the deterministic rebuild of a scikit-learn fit, scored without scikit-learn."""

from __future__ import annotations

import json
from importlib import resources

import pytest

from hexar.agent.classifier import MODEL_FILE, QuestionClassifier, examples
from hexar.agent.router_training import export, fit
from hexar.evals.cases import cases
from tests.agent.test_questions import ACCEPTED


@pytest.fixture(scope="module")
def pipeline() -> object:
    return fit()


def test_shipped_weights_are_the_deterministic_rebuild(pipeline: object) -> None:
    shipped = json.loads(resources.files("hexar.agent").joinpath(MODEL_FILE).read_text("utf-8"))
    assert json.dumps(export(pipeline), sort_keys=True) == json.dumps(shipped, sort_keys=True)


def test_plain_scores_equal_the_fitted_pipeline(pipeline: object) -> None:
    router = QuestionClassifier()
    texts = [q for qs in examples().values() for q in qs] + [c.question for c in cases()] + [a[0] for a in ACCEPTED]
    texts += ["", "WHY   did\tyou  stop?!", "x", "a b", "é à ü"]
    probs = pipeline.predict_proba([t.lower() for t in texts])  # type: ignore[attr-defined]
    for text, row in zip(texts, probs, strict=True):
        scores = router.scores(text)
        assert list(scores) == [str(c) for c in pipeline.classes_]  # type: ignore[attr-defined]
        assert max(abs(scores[label] - p) for label, p in zip(scores, row, strict=True)) < 1e-9, text


def test_choice_is_masked_by_the_task(pipeline: object) -> None:
    router = QuestionClassifier()
    assert router.choose("why did you stop talking", ["planner", "text_to_speech"])[0] == "text_to_speech"
    label, share = router.choose("why did you stop talking", ["planner", "navigation"])
    assert label != "text_to_speech" and 0 < share <= 1
