"""Simulated `recommend_pizza` skill (scenario 20): the request and the tree's recommendation on its topic."""

from __future__ import annotations

import json
import random
from collections.abc import Sequence

from hexar.evals.scenarios.bag import BagBuilder, SkillResult, sec_ns
from hexar.events.contract import PIZZA_EVENTS, PIZZA_STATUS_NAME
from hexar.explainers.pizza.recommender import UnknownIngredientError, default_recommender

MODULE = ("Module name", "skill_recommend_pizza")

# What the person has, per instruction variant: a Margherita set, a spicy-salami set, a vegetable set.
BASES: dict[int, tuple[str, ...]] = {
    1: ("tomato_sauce", "mozzarella", "basil", "olive_oil"),
    2: ("tomato_sauce", "mozzarella", "spicy_salami", "chili"),
    3: ("tomato_sauce", "mozzarella", "bell_peppers", "zucchini", "eggplant", "onion"),
}
# Things a kitchen has anyway; none decides a pizza on its own (tests check the recommendation holds).
PANTRY: tuple[str, ...] = ("parmesan", "olive_oil", "capers", "fontina", "onion", "ham", "bacon")


def scenario_ingredients(variant: int, rng: random.Random) -> list[str]:
    """The available ingredients of instruction `variant` (1-3), with two pantry items in a shuffled order."""
    if variant not in BASES:
        raise ValueError(f"pizza scenario variant must be 1, 2 or 3, not {variant}")
    base = list(BASES[variant])
    extras = rng.sample([p for p in PANTRY if p not in base], 2)
    items = base + extras
    rng.shuffle(items)
    return items


def simulate_recommend_pizza(
    b: BagBuilder, rng: random.Random, start: int, available: Sequence[str]
) -> SkillResult:
    """Publish the request, then the recommendation after the tree's (short) think time.

    An ingredient the recipe data lacks makes the skill fail after its request, as the real skill would.
    """
    t = start + sec_ns(rng.uniform(0.05, 0.2))
    b.status(t, PIZZA_EVENTS, PIZZA_STATUS_NAME, "request",
             [MODULE, ("available_ingredients", json.dumps(list(available)))])
    try:
        pizza = default_recommender().recommend(available)
    except UnknownIngredientError as err:
        return SkillResult(end=t + sec_ns(rng.uniform(0.1, 0.3)), succeeded=False, error_msg=str(err))
    t += sec_ns(rng.uniform(0.3, 0.9))
    b.status(t, PIZZA_EVENTS, PIZZA_STATUS_NAME, "recommendation", [MODULE, ("recommended_pizza", pizza)])
    return SkillResult(end=t + sec_ns(rng.uniform(0.05, 0.2)), succeeded=True)
