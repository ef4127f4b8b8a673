"""The two questions people ask a recommender after "why?": "why not a Pepperoni?" and "what would you have
recommended without basil?". Both are answered by asking the same decision tree again with the ingredients
changed, so the answer is computed, never guessed; an ingredient or pizza the recipe data lacks is said so.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from itertools import combinations
from typing import TYPE_CHECKING

from hexar.explainers.pizza.explainer import a_pizza, pretty
from hexar.explainers.recorded import join_words

if TYPE_CHECKING:
    from hexar.explainers.pizza.recommender import PizzaRecommender

# Words just before an ingredient that take it away or add it ("without basil", "if I had no basil",
# "with pineapple too", "if I had had ham"); taking away is checked first, since "had no" holds "had".
_REMOVE = re.compile(r"\b(without|no|not|minus|except|hadn't|didn't have|did not have|don't have|do not have|"
                     r"had no|out of|instead of)\s+(any\s+|the\s+|some\s+)?$")
_ADD = re.compile(r"\b(with|had|have|plus|add|added|adding|also|and|got|some|extra)\s+(any\s+|the\s+|some\s+)?$")
_WHY_NOT = re.compile(r"\bwhy (not|no|didn't you|did you not|wasn't it|isn't it)\b|\binstead of\b|\brather than\b|"
                      r"\bwhat about\b|\bhow about\b")
# "Would a Diavola have worked?", "could I have made a Hawaiian?", "what does a Hawaiian need?": a "why not" too.
_COULD = re.compile(r"\b(could|would|can|might) (you|i|we) (have )?(made|make|cook(ed)?|recommend(ed)?|suggest(ed)?|"
                    r"pick(ed)?|choose|chosen|go(ne)? with|had)\b|"
                    r"\bwould (a|an|the)\b.*\b(have )?(work(ed)?|been|do(ne)?)\b|"
                    r"\bwhat (would|does|do|did) (a|an|the|i|we) (\w+ )*(have )?need\b")
# "What ingredients did I have?": the recorded request, said back.
_HAD = re.compile(r"\b(what|which) ingredients\b|\bwhat (did|do) (i|we) (have|tell you|give you)\b|"
                  r"\bwhat (was|is) in (the|my|our) (fridge|kitchen|pantry)\b|"
                  # "what did you see we had in the fridge?", "what was available?"
                  r"\bwhat did you (see|find|think|know) (we|i) (had|have)\b|\bwhat (was|were) (available|there)\b")
# The words after the last of these in a "what if" are what it adds or takes away, whether the recipe data knows
# them or not ("what if I had truffles?"); words that are no food stop the reading.
_CHANGE_WORD = re.compile(r"\b(had|have|with|without|no|plus|add|added|adding|also|got|instead of)\s+")
_NOT_FOOD = frozenset({"i", "you", "we", "it", "that", "this", "them", "one", "time", "money", "help", "been",
                       "nothing", "everything", "something", "anything", "more", "less", "fewer", "to", "a", "an",
                       "had", "have", "asked", "said", "told", "wanted", "known", "pizza", "pizzas", "ingredients",
                       "ingredient", "any", "those", "these", "none", "else", "other", "another", "different"})
_DETERMINERS = re.compile(r"^((some|any|the|a|an|extra|fresh|more|also|too|as well)\s+)+")
_TRAILING = re.compile(r"(\s+(too|as well|also|instead|then|again|please|at home|in the fridge))+$")
_WHAT_IF = re.compile(r"\bwhat (if|would you|would it|would have)\b|\bwould you (have )?(still )?(recommend|suggest|"
                      r"pick|choose)\b|\bif i (had|hadn't|didn't|did not|had not)\b|\bhad i\b|\bwithout\b")


MAX_CHANGE = 4  # ingredients added or taken away in a "why not ...?" answer: a bigger change is a new recipe


@dataclass(frozen=True)
class Change:
    removed: tuple[str, ...]
    added: tuple[str, ...]
    unknown: tuple[str, ...] = ()  # words the question adds or takes away that the recipe data lacks


def _names(name: str) -> list[str]:
    spoken = pretty(name).lower()
    return [spoken, spoken[:-1]] if spoken.endswith("s") else [spoken, spoken + "s"]


def asked_pizza(question: str, classes: list[str], recommended: str) -> str | None:
    """The pizza a "why not ...?" question names other than the one recommended, if it asks why not."""
    q = question.lower()
    if not _WHY_NOT.search(q) and not _COULD.search(q):
        return None
    for name in sorted(classes, key=len, reverse=True):  # "Quattro Formaggi" before any shorter name inside it
        if name.lower() != recommended.lower() and re.search(rf"\b{re.escape(name.lower())}\b", q):
            return name
    return None


def asked_change(question: str, ingredients: list[str]) -> Change | None:
    """The ingredients a "what if ...?" question takes away or adds, as the recipe data names them."""
    q = question.lower().replace("_", " ")
    if not _WHAT_IF.search(q) and " with " not in f" {q} ":
        return None
    removed: list[str] = []
    added: list[str] = []
    for ingredient in ingredients:
        for spoken in _names(ingredient):
            m = re.search(rf"\b{re.escape(spoken)}\b", q)
            if m is None:
                continue
            before = q[max(0, m.start() - 40):m.start()]
            if _REMOVE.search(before):
                removed.append(ingredient)
            elif _ADD.search(before) or re.search(r",\s*$|\band\s+$", before):
                added.append(ingredient)
            break
    unknown = tuple(_unknown(q, ingredients))
    return Change(tuple(removed), tuple(added), unknown) if removed or added or unknown else None


# "How sure are you?": the tree's own class probabilities for the recorded ingredients, not a confidence made up.
_SURE = re.compile(r"\bhow (sure|certain|confident)\b|\b(are|were) you (really |quite |very |completely )?"
                   r"(sure|certain|confident)\b|\bhow (likely|probable)\b")


def asks_how_sure(question: str) -> bool:
    return _SURE.search(question.lower()) is not None


def how_sure(rec: PizzaRecommender, known: list[str], pizza: str) -> str:
    """How sure the recipe model is of `pizza` for these ingredients: the share its leaf gives it (a decision tree's
    probability; the shipped recipes are distinct, so every leaf holds one pizza and the share is whole)."""
    label = rec.class_index(pizza)
    share = float(rec.predict_proba(rec.vector(known).reshape(1, -1))[0][label]) if label is not None else 0.0
    alone = "alone" if share >= 0.999 else f"in {share:.0%} of the recipes its rules reach"
    return (f"As sure as my recipe model can be: it is a decision tree learned from {len(rec.labels)} recipes of "
            f"{len(rec.classes)} pizzas, and for the ingredients you had its rules lead to {a_pizza(pizza)} {alone}. "
            "It knows no pizza outside those recipes, though.")


def asks_what_was_had(question: str) -> bool:
    return _HAD.search(question.lower()) is not None


def _unknown(q: str, ingredients: list[str]) -> list[str]:
    """The words after the question's last change word that name no ingredient of the recipe data: "truffles" in
    "what if I had truffles and basil?". A phrase with a word that is no food ("more time") names none."""
    found = list(_CHANGE_WORD.finditer(q))
    if not found:
        return []
    tail = re.split(r"[?.!;]|\b(instead|would|could|then|what|how|do|does|did|is|was)\b", q[found[-1].end():])[0]
    known = {n for i in ingredients for n in _names(i)}
    out = []
    for item in re.split(r",|\band\b|\bor\b|\bplus\b", tail):
        words = _TRAILING.sub("", _DETERMINERS.sub("", item.strip()).strip())
        if not words or words in known or len(words.split()) > 2 or not re.fullmatch(r"[a-z][a-z ]*", words):
            continue
        if _NOT_FOOD.isdisjoint(words.split()):
            out.append(words)
    return out


def _pretty(names: list[str] | tuple[str, ...], last: str = "and") -> str:
    return join_words([pretty(n) for n in names], last)


def what_if(rec: PizzaRecommender, known: list[str], pizza: str, change: Change) -> str:
    """The recommendation for the changed ingredients, from the same tree."""
    not_had = [r for r in change.removed if r not in known]
    taken = [r for r in change.removed if r in known]
    had = [a for a in change.added if a in known]
    new = [a for a in change.added if a not in known]
    other = rec.recommend([*(k for k in known if k not in taken), *new])
    parts = []
    if taken:
        parts.append(f"without {_pretty(taken)}")
    if new:
        parts.append(f"with {_pretty(new)} as well")
    notes = []
    if change.unknown:
        many = len(change.unknown) > 1 or re.search(r"[^s]s$", change.unknown[0]) is not None  # "truffles are"
        notes.append(f"{_pretty(change.unknown).capitalize()} {'are' if many else 'is'} not in my recipe data, so "
                     f"{'they' if many else 'it'} could not change what I recommend.")
    if not_had:
        notes.append(f"You didn't have {_pretty(not_had, 'or')} in the first place.")
    if had:
        notes.append(f"You already had {_pretty(had)}.")
    if not parts:
        return " ".join([*notes, f"So I would still recommend {a_pizza(pizza)}."])
    when = " and ".join(parts)
    said = (f"{when[0].upper()}{when[1:]}, I would still have recommended {a_pizza(pizza)}." if other == pizza
            else f"{when[0].upper()}{when[1:]}, I would have recommended {a_pizza(other)} instead of {a_pizza(pizza)}.")
    return " ".join([*notes, said])


def why_not(rec: PizzaRecommender, known: list[str], pizza: str, wanted: str) -> str:
    """What kept the asked-for pizza out: the smallest change to what you had (ingredients of its recipes added,
    at most one of yours taken away) that makes the same tree pick it, else what its closest recipe needs."""
    have = set(known)
    lead = f"I recommended {a_pizza(pizza)}, not {a_pizza(wanted)}"
    recipes = [[name for name, v in zip(rec.ingredients, row, strict=True) if v]
               for label, row in zip(rec.labels, rec.data, strict=True) if label == wanted]
    closest = min(recipes, key=lambda r: (len([i for i in r if i not in have]), len(r)))
    missing = [i for i in closest if i not in have]
    if not missing:
        return (f"{lead}: you had everything {a_pizza(wanted)} needs, but my recipe model picks {a_pizza(pizza)} "
                "for all that you had.")
    lacking = sorted({i for r in recipes for i in r if i not in have}, key=rec.ingredients.index)
    changes = [(added, removed) for size in range(1, MAX_CHANGE + 1) for removed in ([()] + [(k,) for k in known])
               for added in combinations(lacking, size - len(removed))]
    picks = rec.recommend_many([[*(k for k in known if k not in removed), *added] for added, removed in changes])
    found = next((change for change, pick in zip(changes, picks, strict=True) if pick == wanted), None)
    if found is None:
        return (f"{lead}: {a_pizza(wanted)} needs {_pretty(missing)}, which you "
                f"didn't have, and even with {'it' if len(missing) == 1 else 'them'} my recipe model picks "
                f"{a_pizza(rec.recommend([*known, *missing]))}.")
    added, removed = found
    then = f"I would have recommended {a_pizza(wanted)}"
    if not removed:
        return f"{lead}, because you didn't have {_pretty(added)}: with {'it' if len(added) == 1 else 'them'}, {then}."
    if not added:
        return f"{lead}, because you had {_pretty(removed)}: without it, {then}."
    return (f"{lead}: you didn't have {_pretty(added)}, and you had "
            f"{_pretty(removed)}; with {_pretty(added)} and without {_pretty(removed)}, {then}.")
