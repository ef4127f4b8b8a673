"""The pizza recommender: a decision tree over the recipes shipped with the package (paper section IV)."""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable
from functools import lru_cache
from importlib import resources

import numpy as np
import numpy.typing as npt
from sklearn.tree import DecisionTreeClassifier

from hexar.explainers.errors import ExplainerError

RECIPES = "recipes.csv"
LABEL = "pizza"
RANDOM_STATE = 0

Matrix = npt.NDArray[np.float64]


class UnknownIngredientError(ExplainerError):
    """An ingredient name that the recipe data set does not know."""


def normalise(name: str) -> str:
    """`Tomato sauce`, `tomato-sauce` and `tomato_sauce` are one ingredient."""
    return "_".join(name.strip().lower().replace("-", " ").split())


def load_recipes() -> tuple[list[str], list[str], Matrix]:
    """(ingredient columns, pizza label per row, 0/1 matrix) of the packaged recipe file."""
    text = resources.files("hexar.explainers.pizza").joinpath(RECIPES).read_text(encoding="utf-8")
    rows = list(csv.reader(io.StringIO(text)))
    header, body = rows[0], [r for r in rows[1:] if r]
    if not header or header[0] != LABEL:
        raise ExplainerError(f"{RECIPES}: the first column must be {LABEL!r}")
    ingredients = header[1:]
    labels = [r[0] for r in body]
    matrix = np.array([[float(v) for v in r[1:]] for r in body], dtype=np.float64)
    return ingredients, labels, matrix


class PizzaRecommender:
    """Which pizza to make from the ingredients at hand.

    The tree is fitted on arrays rather than a data frame, so that LIME's sampled arrays are valid input.
    """

    def __init__(self) -> None:
        self.ingredients, self.labels, self.data = load_recipes()
        self._index = {name: i for i, name in enumerate(self.ingredients)}
        self.tree = DecisionTreeClassifier(random_state=RANDOM_STATE)
        self.tree.fit(self.data, np.array(self.labels))
        self.classes: list[str] = [str(c) for c in self.tree.classes_]

    def vector(self, available: Iterable[str]) -> Matrix:
        """The 0/1 feature row of the available ingredients."""
        row = np.zeros(len(self.ingredients), dtype=np.float64)
        unknown = []
        for name in available:
            i = self._index.get(normalise(name))
            if i is None:
                unknown.append(name)
            else:
                row[i] = 1.0
        if unknown:
            raise UnknownIngredientError(
                f"unknown ingredient(s) {', '.join(map(repr, unknown))}; known: {', '.join(self.ingredients)}"
            )
        return row

    def known(self, available: Iterable[str]) -> tuple[list[str], list[str]]:
        """(known ingredient names normalised, unknown names as given): a recording may hold names we lack."""
        known: list[str] = []
        unknown: list[str] = []
        for name in available:
            (known if normalise(name) in self._index else unknown).append(name)
        return [normalise(n) for n in known], unknown

    def recommend(self, available: Iterable[str]) -> str:
        return str(self.tree.predict(self.vector(available).reshape(1, -1))[0])

    def recommend_many(self, sets: list[list[str]]) -> list[str]:
        """One tree prediction for many ingredient sets: a search over changed sets stays one call."""
        if not sets:
            return []
        return [str(p) for p in self.tree.predict(np.stack([self.vector(s) for s in sets]))]

    def predict_proba(self, rows: Matrix) -> Matrix:
        """Class probabilities in the order of `classes`, for rows of 0/1 features (LIME's classifier_fn)."""
        return np.asarray(self.tree.predict_proba(np.asarray(rows, dtype=np.float64)), dtype=np.float64)

    def split_features(self) -> set[str]:
        """The ingredients that the fitted tree tests at some node; leaves carry a negative feature index."""
        return {self.ingredients[int(f)] for f in self.tree.tree_.feature if int(f) >= 0}

    def class_index(self, pizza: str) -> int | None:
        wanted = pizza.strip().lower()
        for i, name in enumerate(self.classes):
            if name.lower() == wanted:
                return i
        return None


@lru_cache(maxsize=1)
def default_recommender() -> PizzaRecommender:
    """One fitted recommender per process: the data set is fixed, so refitting would give the same tree."""
    return PizzaRecommender()
