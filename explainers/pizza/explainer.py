"""Why this pizza: LIME over the recommender's decision tree, for the recorded request (paper section IV)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

from hexar.events.contract import PIZZA_EVENTS, PIZZA_STATUS_NAME
from hexar.events.records import StatusRecord
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.recorded import join_words

if TYPE_CHECKING:
    from hexar.explainers.pizza.recommender import PizzaRecommender
    from hexar.explainers.registry import Registry

CAUSE = "pizza.ingredients"
MISMATCH = "pizza.model_mismatch"
# the skill's request holds the ingredients it was given (available_ingredients), not who gave them: never "you told me"
GIVEN = "The ingredients I was given as available were"
LIME_SAMPLES = 1000
LIME_SEED = 0
# LIME fits a local linear model to sampled outputs, so ingredients the tree never tests still get small
# non-zero weights; anything under this share of the strongest weight is sampling noise, not a reason.
MIN_SHARE = 0.2


@dataclass(frozen=True)
class Weight:
    ingredient: str
    present: bool
    weight: float


def pretty(ingredient: str) -> str:
    return ingredient.replace("_", " ")


def a_pizza(name: str) -> str:
    return f"{'an' if name[:1].lower() in 'aeio' else 'a'} {name}"


def _strength(weight: float, strongest: float) -> str:
    share = abs(weight) / strongest if strongest > 0 else 0.0
    return "strongly" if share >= 0.5 else "somewhat" if share >= MIN_SHARE else "slightly"


def weighed(pizza: str, weights: list[Weight], strongest: float, most: int = 4) -> list[str]:
    """LIME's weights said as a person would: what spoke for the pizza and what against, strongest first.
    Only weights of at least a twentieth of the strongest are named: the rest is LIME's sampling noise."""
    named = [w for w in weights if strongest > 0 and abs(w.weight) >= strongest / 20]

    def words(w: Weight) -> str:
        have = f"you have {pretty(w.ingredient)}" if w.present else f"you have no {pretty(w.ingredient)}"
        return f"that {have} ({_strength(w.weight, strongest)})"

    pro = [words(w) for w in named if w.weight > 0][:most]
    con = [words(w) for w in named if w.weight < 0][:most - 1]
    out = [f"What weighed most for {a_pizza(pizza)}: {join_words(pro)}." if pro else
           f"Nothing you have spoke clearly for {a_pizza(pizza)}."]
    if con:
        out.append(f"What weighed against it: {join_words(con)}.")
    return out


def lime_weights(recommender: PizzaRecommender, known: list[str], label: int) -> list[Weight]:
    """LIME weights of every ingredient toward class `label` at the recorded ingredient vector.

    A fresh LIME explainer per call: it draws from one RandomState, so a shared one would give different
    weights to the same question asked twice.
    """
    from lime.lime_tabular import LimeTabularExplainer

    features = list(range(len(recommender.ingredients)))
    lime = LimeTabularExplainer(
        recommender.data,
        mode="classification",
        feature_names=recommender.ingredients,
        class_names=recommender.classes,
        categorical_features=features,
        discretize_continuous=False,
        random_state=LIME_SEED,
    )
    row = recommender.vector(known)
    result = lime.explain_instance(
        row, recommender.predict_proba, labels=(label,), num_features=len(features), num_samples=LIME_SAMPLES
    )
    weights = [
        Weight(recommender.ingredients[int(i)], bool(row[int(i)] > 0.5), float(w))
        for i, w in result.as_map()[label]
    ]
    return sorted(weights, key=lambda w: -abs(w.weight))


def _is_pizza_record(r: StatusRecord) -> bool:
    # A robot that leaves the status name empty still follows the topic's message convention.
    return r.name in {PIZZA_STATUS_NAME, ""}


def last_pair(records: list[StatusRecord]) -> tuple[StatusRecord | None, StatusRecord | None]:
    """The last recommendation and the last request before it (or just the last request, if unanswered)."""
    pizza = [r for r in records if _is_pizza_record(r)]
    recommendation = next((r for r in reversed(pizza) if r.message == "recommendation"), None)
    limit = recommendation.t if recommendation is not None else None
    request = next(
        (r for r in reversed(pizza) if r.message == "request" and (limit is None or r.t <= limit)), None
    )
    return request, recommendation


def parse_ingredients(raw: str) -> list[str] | None:
    try:
        value = json.loads(raw)
    except json.JSONDecodeError:
        return None
    if not isinstance(value, list):
        return None
    return [str(v) for v in value]


class PizzaRecommenderExplainer:
    """f_e for the `recommend_pizza` skill: which available ingredients made the tree pick the pizza."""

    name: ClassVar[str] = "pizza_recommender"
    topics: ClassVar[frozenset[str]] = frozenset({PIZZA_EVENTS})
    description: ClassVar[str] = (
        "Explains why the robot recommended a particular pizza. The recommender is a decision tree over a "
        "recipe data set that picks a pizza from the ingredients the person said were available; this "
        "explainer reads the recorded request and recommendation and uses LIME to tell which of those "
        "ingredients pushed the choice toward that pizza, and what the robot would have recommended without "
        "them; asked 'why not a Hawaiian?' or 'what if I had no basil?', it asks the same tree again with the "
        "ingredients changed. Use it for questions like 'why did you suggest a Margherita?' or 'why this pizza?'."
    )

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        # The answer is a template over LIME's numbers; the model is kept for the common constructor only.
        self.model = model
        self.registry = registry

    def explain(self, question: str, context: Context) -> Explanation:
        records = context.view(self.topics).statuses(PIZZA_EVENTS)
        request, recommendation = last_pair(records)
        if recommendation is None:
            reason = (
                "I was asked for a pizza, but no recommendation was recorded."
                if request is not None
                else "No pizza recommendation was recorded in this task."
            )
            return Explanation.not_enough(self.name, reason)
        if request is None:
            return Explanation.not_enough(
                self.name, "The recommendation was recorded, but not the ingredients it was made from."
            )
        raw = request.get("available_ingredients", "") or ""
        available = parse_ingredients(raw)
        pizza = (recommendation.get("recommended_pizza", "") or "").strip()
        if available is None or not pizza:
            return Explanation.not_enough(self.name, "The recorded request or recommendation is unreadable.")

        evidence = [
            Evidence(cause=CAUSE, topic=PIZZA_EVENTS, t=request.t, item=f"available_ingredients = {raw}"),
            Evidence(
                cause=CAUSE, topic=PIZZA_EVENTS, t=recommendation.t, item=f"recommended_pizza = {pizza}"
            ),
        ]
        return self._explain(pizza, available, evidence, question)

    def _explain(self, pizza: str, available: list[str], evidence: list[Evidence], question: str) -> Explanation:
        from hexar.explainers.pizza.recommender import default_recommender

        rec = default_recommender()
        known, unknown = rec.known(available)
        predicted = rec.recommend(known)
        had = join_words([pretty(a) for a in available]) if available else "no ingredients at all"
        model = ("my recipe model still picks the same for them" if predicted == pizza
                 else f"my recipe model picks {a_pizza(predicted)} for them")
        details = [f"{GIVEN} {had}.", f"I recommended {a_pizza(pizza)}, and {model}."]
        if unknown:
            details.append(f"{join_words([pretty(u) for u in unknown]).capitalize()} "
                           f"{'is' if len(unknown) == 1 else 'are'} not in my recipe data, so I left "
                           f"{'it' if len(unknown) == 1 else 'them'} out.")
        if predicted != pizza:
            # the recorded recommendation is what the model disagrees with: it backs the mismatch cause too
            evidence = [*evidence, *(ev.model_copy(update={"cause": MISMATCH}) for ev in evidence[1:])]
        label = rec.class_index(pizza)
        if label is None:
            text = (
                f"I recommended {a_pizza(pizza)}, but that pizza is not in my recipe data, so I can't say "
                f"which ingredients led to it; from the same ingredients my model picks {a_pizza(predicted)}."
            )
            return Explanation(explainer=self.name, text=text, causes=[MISMATCH], evidence=evidence,
                               details=details, confidence=0.3)
        pizza = rec.classes[label]
        weights = lime_weights(rec, known, label)
        strongest = max((abs(w.weight) for w in weights), default=0.0)
        details.extend(weighed(pizza, weights, strongest))
        figures = [f"LIME weights toward {pizza} (ingredient, present?, weight), strongest first:"]
        figures.extend(f"  {w.ingredient}, {'present' if w.present else 'absent'}, {w.weight:+.3f}"
                       for w in weights if abs(w.weight) >= 0.001)
        floor = max(MIN_SHARE * strongest, 1e-6)
        # An ingredient the tree never tests cannot have changed its choice, whatever LIME's noise says.
        used = rec.split_features()
        strong = [w for w in weights if w.weight >= floor and w.ingredient in used]
        reasons = [w.ingredient for w in strong if w.present][:3]
        missing = [w.ingredient for w in strong if not w.present][:2]

        have = join_words([pretty(r) for r in reasons]) if reasons else ""
        sentences = []
        if predicted == pizza:
            if reasons:
                sentences.append(f"I recommended {a_pizza(pizza)} because you have {have}.")
            else:
                sentences.append(f"I recommended {a_pizza(pizza)} because none of your ingredients pointed "
                                 "more strongly to another pizza.")
        else:
            sentences.append(
                f"I recommended {a_pizza(pizza)}, but my recipe model now picks {a_pizza(predicted)} for the "
                "same ingredients, so the recording and the model disagree."
            )
            if reasons:
                sentences.append(f"What speaks for {a_pizza(pizza)} is that you have {have}.")
        if missing:
            also = " also" if reasons else ""
            sentences.append(f"Not having {join_words([pretty(m) for m in missing], 'or')}{also} pointed to it.")
        if predicted == pizza:
            # "why not a Pepperoni?", "and without basil?": the same tree asked again, in place of the why
            sentences = _asked(rec, known, pizza, question) or sentences
        causes = [CAUSE] if predicted == pizza else [CAUSE, MISMATCH]
        return Explanation(
            explainer=self.name,
            text=" ".join(sentences),
            causes=causes,
            evidence=evidence,
            # Only when the model agrees with the recording can removing an ingredient change its answer.
            counterfactual=self._counterfactual(rec, known, reasons, pizza) if predicted == pizza else None,
            details=details,
            figures=figures,
            confidence=1.0 if predicted == pizza else 0.5,
        )

    @staticmethod
    def _counterfactual(
        rec: PizzaRecommender, known: list[str], reasons: list[str], pizza: str
    ) -> str | None:
        """Ask the tree what it picks without each reason in turn, so the claim is computed, not guessed."""
        for ingredient in reasons:
            other = rec.recommend([k for k in known if k != ingredient])
            if other != pizza:
                return f"Had you not had {pretty(ingredient)}, I would have recommended {a_pizza(other)}."
        return None


def _asked(rec: PizzaRecommender, known: list[str], pizza: str, question: str) -> list[str]:
    # imported here: whatif words its answers with this module's pretty() and a_pizza()
    from hexar.explainers.pizza.whatif import (
        asked_change,
        asked_pizza,
        asks_how_sure,
        asks_what_was_had,
        how_sure,
        what_if,
        why_not,
    )

    if asks_how_sure(question):
        return [how_sure(rec, known, pizza)]
    if asks_what_was_had(question):
        had = join_words([pretty(k) for k in known]) if known else "none of the ingredients my recipes know"
        return [f"{GIVEN} {had}, and from that I recommended {a_pizza(pizza)}."]
    wanted = asked_pizza(question, rec.classes, pizza)
    if wanted is not None:
        return [why_not(rec, known, pizza, wanted)]
    change = asked_change(question, rec.ingredients)
    return [what_if(rec, known, pizza, change)] if change is not None else []
