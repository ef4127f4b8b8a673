from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from hexar.evals.scenarios.bag import BagBuilder, sec_ns
from hexar.evals.scenarios.pizza import PANTRY, scenario_ingredients, simulate_recommend_pizza
from hexar.events.contract import PIZZA_EVENTS, PIZZA_STATUS_NAME
from hexar.events.reader import read_recording
from hexar.explainers.pizza.recommender import default_recommender

T0 = 1_700_000_000 * 1_000_000_000
EXPECTED = {1: "Margherita", 2: "Diavola", 3: "Vegetariana"}


@pytest.mark.parametrize("variant", [1, 2, 3])
def test_variants_lead_to_their_pizza_whatever_the_pantry(variant: int) -> None:
    rec = default_recommender()
    for seed in range(40):
        items = scenario_ingredients(variant, random.Random(seed))
        assert len(items) == len(set(items))
        assert any(p in items for p in PANTRY)
        assert rec.recommend(items) == EXPECTED[variant]


def test_ingredients_are_reproducible() -> None:
    assert scenario_ingredients(2, random.Random(5)) == scenario_ingredients(2, random.Random(5))
    with pytest.raises(ValueError):
        scenario_ingredients(4, random.Random(0))


def test_simulated_skill_writes_request_then_recommendation(tmp_path: Path) -> None:
    b = BagBuilder()
    available = scenario_ingredients(1, random.Random(1))
    result = simulate_recommend_pizza(b, random.Random(1), T0, available)
    assert result.succeeded and result.error_msg == ""
    assert T0 < result.end < T0 + sec_ns(1.5)
    log = read_recording(b.write(tmp_path / "bag"))
    request, answer = log.statuses[PIZZA_EVENTS]
    assert request.name == answer.name == PIZZA_STATUS_NAME
    assert (request.message, answer.message) == ("request", "recommendation")
    assert json.loads(request.get("available_ingredients") or "") == available
    assert answer.get("recommended_pizza") == "Margherita"
    assert T0 < request.t < answer.t < result.end


def test_unknown_ingredient_fails_the_skill() -> None:
    b = BagBuilder()
    result = simulate_recommend_pizza(b, random.Random(0), T0, ["mozzarella", "dragon fruit"])
    assert not result.succeeded and "dragon fruit" in result.error_msg
    assert [m[1] for m in b.messages] == [PIZZA_EVENTS]
