"""The router's shipped weights: the deterministic rebuild of a scikit-learn fit, scored without scikit-learn."""

from __future__ import annotations

import json
import math
from importlib import resources

import pytest

from hexar.agent.classifier import MODEL_FILE, QuestionClassifier, examples
from hexar.agent.router_training import export, fit
from hexar.evals.cases import cases
from tests.agent.test_questions import ACCEPTED


@pytest.fixture(scope="module")
def pipeline() -> object:
    return fit()


# "The same model": the same labels, terms and settings, and every number equal to within what a BLAS build or a
# scikit-learn/numpy release changes in the last bits of a fit (seen: 1e-13). Far below what moves a score.
REL_TOL = 1e-9
ABS_TOL = 1e-10


def _same(rebuilt: object, shipped: object, where: str) -> list[str]:
    if isinstance(rebuilt, dict) and isinstance(shipped, dict):
        if sorted(rebuilt) != sorted(shipped):
            return [f"{where}: keys differ ({sorted(set(rebuilt) ^ set(shipped))[:5]})"]
        return [d for k in rebuilt for d in _same(rebuilt[k], shipped[k], f"{where}/{k}")]
    if isinstance(rebuilt, list) and isinstance(shipped, list):
        if len(rebuilt) != len(shipped):
            return [f"{where}: {len(rebuilt)} values, shipped {len(shipped)}"]
        return [d for i, (a, b) in enumerate(zip(rebuilt, shipped, strict=True)) for d in _same(a, b, f"{where}[{i}]")]
    if isinstance(rebuilt, float) or isinstance(shipped, float):
        ok = isinstance(rebuilt, int | float) and isinstance(shipped, int | float)
        if ok and math.isclose(rebuilt, shipped, rel_tol=REL_TOL, abs_tol=ABS_TOL):  # type: ignore[arg-type]
            return []
        return [f"{where}: {rebuilt!r} rebuilt, {shipped!r} shipped"]
    return [] if rebuilt == shipped else [f"{where}: {rebuilt!r} rebuilt, {shipped!r} shipped"]


def test_shipped_weights_are_the_deterministic_rebuild(pipeline: object) -> None:
    shipped = json.loads(resources.files("hexar.agent").joinpath(MODEL_FILE).read_text("utf-8"))
    differences = _same(export(pipeline), shipped, "router_model")
    assert not differences, f"{len(differences)} differ, first: {differences[:3]}; rebuild: scripts/train_router.py"


def test_the_tolerance_still_tells_another_model_apart(pipeline: object) -> None:
    rebuilt = export(pipeline)
    nudged = json.loads(json.dumps(rebuilt))
    nudged["intercept"][0] += 1e-6  # a millionth: far below a fit from other examples, far above BLAS noise
    assert _same(rebuilt, nudged, "m") and not _same(rebuilt, json.loads(json.dumps(rebuilt)), "m")
    nudged = json.loads(json.dumps(rebuilt))
    nudged["words"]["terms"].pop(next(iter(nudged["words"]["terms"])))
    assert _same(rebuilt, nudged, "m")


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
