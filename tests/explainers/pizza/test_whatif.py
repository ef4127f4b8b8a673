"""'Why not a Hawaiian?' and 'what if I had no basil?' are answered by asking the same tree again."""

from __future__ import annotations

from collections.abc import Callable

from hexar.events.log import EventLog
from hexar.explainers.base import Context
from hexar.explainers.pizza import PizzaRecommenderExplainer
from hexar.explainers.pizza.recommender import default_recommender
from hexar.explainers.pizza.whatif import Change, asked_change, asked_pizza

MakeBag = Callable[..., EventLog]
AVAILABLE = ["tomato_sauce", "mozzarella", "basil", "olive_oil", "capers"]


def _ask(log: EventLog, question: str) -> str:
    return PizzaRecommenderExplainer().explain(question, Context.for_task(log, log.task())).text


def test_without_an_ingredient_says_what_the_tree_picks_then(pizza_bag: MakeBag) -> None:
    log = pizza_bag(AVAILABLE)
    then = default_recommender().recommend([a for a in AVAILABLE if a != "basil"])
    assert then != "Margherita"  # basil decided it: the answer must name another pizza
    for question in ("What would you have recommended without basil?", "what if i had no basil"):
        assert _ask(log, question) == f"Without basil, I would have recommended a {then} instead of a Margherita."
    why = PizzaRecommenderExplainer().explain("Why this pizza?", Context.for_task(log, log.task()))
    assert why.counterfactual == f"Had you not had basil, I would have recommended a {then}."
    # an ingredient that changes nothing, and one that was never there
    assert _ask(log, "What if I had no capers?") == "Without capers, I would still have recommended a Margherita."
    assert _ask(log, "what if I didn't have olives") == ("You didn't have olives in the first place. So I would "
                                                         "still recommend a Margherita.")


def test_why_not_another_pizza_names_what_it_lacked(pizza_bag: MakeBag) -> None:
    log = pizza_bag(AVAILABLE)
    assert default_recommender().recommend([*AVAILABLE, "pineapple"]) == "Hawaiian"
    assert _ask(log, "Why not a Hawaiian?") == ("I recommended a Margherita, not a Hawaiian, because you didn't have "
                                                "pineapple: with it, I would have recommended a Hawaiian.")
    # every pizza asked about: what the answer says would have changed the choice does, in the same tree
    rec = default_recommender()
    for wanted in rec.classes:
        text = _ask(log, f"why didn't you suggest a {wanted.lower()}")
        if wanted == "Margherita":
            continue
        assert text.startswith(f"I recommended a Margherita, not a{'n' if wanted[0] in 'AEIO' else ''} {wanted}")
        if "because you didn't have " in text:
            lacked = _named(text.split("because you didn't have ")[1].split(":")[0])
            assert rec.recommend([*AVAILABLE, *lacked]) == wanted, text
        elif "because you had " in text:
            had = _named(text.split("because you had ")[1].split(":")[0])
            assert rec.recommend([a for a in AVAILABLE if a not in had]) == wanted, text
        elif "and without " in text:
            lacked = _named(text.split("; with ")[1].split(" and without ")[0])
            had = _named(text.split(" and without ")[1].split(",")[0])
            assert rec.recommend([*(a for a in AVAILABLE if a not in had), *lacked]) == wanted, text
        else:
            assert "even with" in text and "my recipe model picks a Margherita" in text, text
    # the plain why keeps its LIME answer
    assert _ask(log, "Why a Margherita?").startswith("I recommended a Margherita because you have basil")


def _named(words: str) -> list[str]:
    return [w.strip().replace(" ", "_") for w in words.replace(" and ", ", ").split(", ")]


def test_which_questions_change_the_ingredients_or_name_another_pizza() -> None:
    rec = default_recommender()
    assert asked_change("What if I had pineapple too?", rec.ingredients) == Change((), ("pineapple",))
    assert asked_change("would you still pick it with ham and mushrooms", rec.ingredients) == \
        Change((), ("ham", "mushrooms"))
    assert asked_change("and without the mozzarella?", rec.ingredients) == Change(("mozzarella",), ())
    assert asked_change("Why did you recommend a Margherita?", rec.ingredients) is None
    assert asked_pizza("why not a pepperoni", rec.classes, "Margherita") == "Pepperoni"
    assert asked_pizza("Why a Margherita?", rec.classes, "Margherita") is None
    assert asked_pizza("why not a margherita", rec.classes, "Margherita") is None


def test_an_ingredient_the_recipes_lack_is_said_to_change_nothing(pizza_bag: MakeBag) -> None:
    log = pizza_bag(AVAILABLE)
    assert default_recommender().known([*AVAILABLE, "truffles"]) == (AVAILABLE, ["truffles"])  # left out
    assert _ask(log, "What if I had truffles?") == ("Truffles are not in my recipe data, so they could not change "
                                                    "what I recommend. So I would still recommend a Margherita.")
    assert _ask(log, "what if I had some saffron and basil") == (
        "Saffron is not in my recipe data, so it could not change what I recommend. You already had basil. So I "
        "would still recommend a Margherita.")
    # a known change beside an unknown one is still computed
    assert _ask(log, "What if I had no basil and no cheese?").startswith("Cheese is not in my recipe data")
    # words that are no food leave the plain why
    for question in ("What if I had more time?", "What if I had asked for something spicy?"):
        assert _ask(log, question).startswith("I recommended a Margherita because you have basil"), question


def test_what_was_had_is_the_recorded_request_said_back(pizza_bag: MakeBag) -> None:
    log = pizza_bag(AVAILABLE)
    for question in ("What ingredients did I have?", "what was in the fridge", "What did I tell you?",
                     "What did you see we had in the fridge?"):
        assert _ask(log, question) == ("The ingredients I was given as available were tomato sauce, mozzarella, "
                                       "basil, olive oil and capers, and from that I recommended a Margherita."), \
            question


def test_could_and_would_questions_about_another_pizza_are_why_nots() -> None:
    rec = default_recommender()
    for question in ("Would a Diavola have worked?", "could I have made a diavola", "What does a Diavola need?",
                     "could you have recommended the Diavola instead"):
        assert asked_pizza(question, rec.classes, "Margherita") == "Diavola", question
    assert asked_pizza("Was the Diavola spicy?", rec.classes, "Margherita") is None


def test_how_sure_is_the_trees_own_share_for_the_recorded_ingredients(pizza_bag: MakeBag) -> None:
    """The fitted tree's probability for the recorded ingredients, with what it was learned from; its leaves each
    hold one pizza of the recipe data, so the share is whole, and the answer says what it does not know."""
    rec = default_recommender()
    proba = rec.predict_proba(rec.vector(AVAILABLE).reshape(1, -1))[0]
    assert max(proba) == 1.0 and rec.classes[int(proba.argmax())] == "Margherita"
    log = pizza_bag(AVAILABLE)
    for question in ("How sure are you?", "are you really sure", "how confident are you about the Margherita?"):
        assert _ask(log, question) == (
            f"As sure as my recipe model can be: it is a decision tree learned from {len(rec.labels)} recipes of "
            f"{len(rec.classes)} pizzas, and for the ingredients you had its rules lead to a Margherita alone. It "
            "knows no pizza outside those recipes, though."), question
