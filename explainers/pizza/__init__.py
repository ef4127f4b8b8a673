"""The pizza recommender's explainer: LIME over a decision tree of recipes."""

from __future__ import annotations

from hexar.explainers.pizza.explainer import PizzaRecommenderExplainer

__all__ = ["PizzaRecommenderExplainer"]
