from __future__ import annotations

import pytest

from hexar.explainers.errors import ExplainerError
from hexar.explainers.pizza.explainer import lime_weights
from hexar.explainers.pizza.recommender import PizzaRecommender, UnknownIngredientError, default_recommender

MARGHERITA = ["tomato_sauce", "mozzarella", "basil", "olive_oil"]
SETS = [
    MARGHERITA,
    ["tomato_sauce", "mozzarella", "spicy_salami", "chili", "parmesan"],
    ["tomato_sauce", "mozzarella", "bell_peppers", "zucchini", "eggplant", "onion", "ham"],
    ["mozzarella", "gorgonzola", "parmesan", "fontina"],
    ["bbq_sauce", "mozzarella", "chicken", "onion"],
]


def test_data_set_shape() -> None:
    rec = default_recommender()
    assert rec.data.shape[0] >= 30
    assert len(rec.ingredients) >= 15
    assert set(rec.data.ravel()) <= {0.0, 1.0}
    assert len(rec.classes) >= 10
    # Every recipe of the data set is recommended as itself: the tree fits its training data.
    assert rec.tree.score(rec.data, rec.labels) == 1.0


def test_recommendations_are_plausible() -> None:
    rec = default_recommender()
    assert rec.recommend(MARGHERITA) == "Margherita"
    assert rec.recommend(SETS[1]) == "Diavola"
    assert rec.recommend(SETS[2]) == "Vegetariana"
    assert rec.recommend(SETS[3]) == "Quattro Formaggi"
    assert rec.recommend(SETS[4]) == "BBQ Chicken"


def test_deterministic() -> None:
    a, b = PizzaRecommender(), PizzaRecommender()
    assert a.split_features() == b.split_features()
    for available in SETS:
        assert a.recommend(available) == b.recommend(available)
        assert (a.predict_proba(a.vector(available).reshape(1, -1)) ==
                b.predict_proba(b.vector(available).reshape(1, -1))).all()
    assert default_recommender() is default_recommender()


def test_names_are_normalised() -> None:
    rec = default_recommender()
    assert rec.recommend(["Tomato sauce", " MOZZARELLA", "basil", "olive-oil"]) == "Margherita"


def test_unknown_ingredient() -> None:
    rec = default_recommender()
    with pytest.raises(UnknownIngredientError, match="'unicorn horn'"):
        rec.recommend(["mozzarella", "unicorn horn"])
    assert issubclass(UnknownIngredientError, ExplainerError)


def test_split_features_are_ingredients() -> None:
    rec = default_recommender()
    used = rec.split_features()
    assert used and used <= set(rec.ingredients)
    assert len(used) < len(rec.ingredients)


@pytest.mark.parametrize("available", SETS)
def test_top_lime_ingredient_is_split_on(available: list[str]) -> None:
    rec = default_recommender()
    label = rec.class_index(rec.recommend(available))
    assert label is not None
    weights = lime_weights(rec, available, label)
    assert weights[0].ingredient in rec.split_features()
    # LIME is seeded: the same question gets the same weights.
    assert weights == lime_weights(rec, available, label)
