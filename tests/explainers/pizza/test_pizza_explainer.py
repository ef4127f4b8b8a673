from __future__ import annotations

import time
from collections.abc import Callable
from importlib.metadata import entry_points

from hexar.events.contract import PIZZA_EVENTS
from hexar.events.log import EventLog
from hexar.explainers.base import Context
from hexar.explainers.pizza import PizzaRecommenderExplainer
from hexar.explainers.pizza.recommender import default_recommender
from hexar.explainers.registry import ENTRY_POINT_GROUP

MakeBag = Callable[..., EventLog]


def test_names_pizza_and_present_ingredient(pizza_bag: MakeBag) -> None:
    available = ["tomato_sauce", "mozzarella", "basil", "olive_oil", "capers"]
    log = pizza_bag(available)
    ctx, explainer = Context.for_task(log, log.task()), PizzaRecommenderExplainer()
    t = time.perf_counter()
    exp = explainer.explain("Why this pizza?", ctx)
    assert time.perf_counter() - t < 1.0
    assert exp.enough_information and exp.causes == ["pizza.ingredients"]
    assert exp.text.startswith("I recommended a Margherita because you have basil")
    assert exp.counterfactual is not None and "basil" in exp.counterfactual
    # A second "why?" hears the weights in words; LIME's own numbers stay with the evidence.
    assert "What weighed most for a Margherita: that you have basil (strongly)" in " ".join(exp.details)
    assert not any("LIME" in d or "present," in d or "+0." in d for d in exp.details)
    assert exp.figures[0].startswith("LIME weights toward Margherita")
    assert any(f.strip().startswith("basil, present, +") for f in exp.figures)
    recorded = {(r.t, r.message, v) for r in log.statuses[PIZZA_EVENTS] for _, v in r.data_items()}
    assert {e.item for e in exp.evidence} == {
        f'available_ingredients = {str(available).replace(chr(39), chr(34))}',
        "recommended_pizza = Margherita",
    }
    for e in exp.evidence:
        assert e.topic == PIZZA_EVENTS
        assert any(t == e.t and e.item.endswith(v) for t, _, v in recorded)


def test_spicy_and_vegetable_sets(pizza_bag: MakeBag) -> None:
    rec = default_recommender()
    log = pizza_bag(["chili", "spicy_salami", "mozzarella", "tomato_sauce", "onion"])
    exp = PizzaRecommenderExplainer().explain("why?", Context.for_task(log, log.task()))
    assert "Diavola" in exp.text and "spicy salami" in exp.text
    log = pizza_bag(["tomato_sauce", "mozzarella", "bell_peppers", "zucchini", "eggplant"], seed=3)
    exp = PizzaRecommenderExplainer().explain("why?", Context.for_task(log, log.task()))
    assert "Vegetariana" in exp.text and "bell peppers" in exp.text
    # Only ingredients the tree tests are given as reasons.
    assert "zucchini" not in exp.text and "zucchini" not in rec.split_features()


def test_not_enough_information(pizza_bag: MakeBag) -> None:
    log = pizza_bag([], recommend=False)
    exp = PizzaRecommenderExplainer().explain("Why this pizza?", Context.for_task(log, log.task()))
    assert not exp.enough_information and exp.causes == [] and exp.evidence == []
    assert "No pizza recommendation" in exp.text


def test_recording_that_disagrees_with_model_is_reported(pizza_bag: MakeBag) -> None:
    log = pizza_bag(["tomato_sauce", "mozzarella", "basil"])
    # Another robot's tree may have answered differently: the explainer must say so, not pretend.
    rec = log.statuses[PIZZA_EVENTS][-1]
    patched = rec.__class__(rec.t, rec.topic, rec.level, rec.name, rec.message, rec.hardware_id,
                            (("recommended_pizza", "Diavola"),))
    log.statuses[PIZZA_EVENTS][-1] = patched
    exp = PizzaRecommenderExplainer().explain("why?", Context.for_task(log, log.task()))
    assert "pizza.model_mismatch" in exp.causes
    assert "Diavola" in exp.text and "Margherita" in exp.text and "disagree" in exp.text
    assert exp.confidence < 1.0


def test_unknown_pizza_in_recording(pizza_bag: MakeBag) -> None:
    log = pizza_bag(["tomato_sauce", "mozzarella", "basil"])
    rec = log.statuses[PIZZA_EVENTS][-1]
    log.statuses[PIZZA_EVENTS][-1] = rec.__class__(rec.t, rec.topic, rec.level, rec.name, rec.message,
                                                   rec.hardware_id, (("recommended_pizza", "Calzone"),))
    exp = PizzaRecommenderExplainer().explain("why?", Context.for_task(log, log.task()))
    assert exp.causes == ["pizza.model_mismatch"]
    assert "not in my recipe data" in exp.text


def test_registered_under_its_name() -> None:
    (ep,) = [ep for ep in entry_points(group=ENTRY_POINT_GROUP) if ep.name == "pizza_recommender"]
    assert ep.load() is PizzaRecommenderExplainer
    explainer = PizzaRecommenderExplainer(model=None, registry=None)
    assert explainer.topics == frozenset({PIZZA_EVENTS})
    assert "pizza" in explainer.description
