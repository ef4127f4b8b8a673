"""`hexar eval --suite real-nav2`: HEXAR on recordings made from real Nav2 console excerpts (evals/real_nav2.py),
graded against the cause each public thread diagnosed.

Per excerpt, from the answer's text (the claims reader the paper's graders use, hexar/claims.py):
- cause named: the answer affirms the diagnosed cause; counted over the excerpts whose pasted lines show it.
- unsupported cause: the answer affirms a cause that is not the diagnosed one (nor one it implies, nor one that
  implies it, i.e. the same cause in more detail, nor an honest "not enough information" finding), or says nothing
  went wrong of a failed run / that a finished run failed.
- honest not-enough: the answer names no unsupported cause and says the logs do not show why
  (navigation.no_progress, navigation.unexplained_failure, or those words); counted apart from wrong.
Each excerpt ends in one verdict: `named`, `honest` or `wrong`. The cause ids HEXAR returned are graded the same
way beside the text (`structured`), never instead of it.
"""

from __future__ import annotations

import re
import tempfile
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass
from functools import partial
from pathlib import Path
from typing import Any

from hexar.agent.backends import Backend
from hexar.causes import vocabulary
from hexar.claims import ALL_FINE, TASK_FAILED, read_claims
from hexar.errors import USER_ERRORS
from hexar.evals.real_nav2 import (
    BLIND_FILES,
    DISTROS,
    Excerpt,
    blind_set,
    corpus,
    heldout,
    read_cases,
    task_plan,
    write_recording,
)

SUITE = "real-nav2"
# The same suite on threads the catalogue was never tuned on (evals/data/real_nav2/heldout.yaml).
HELDOUT_SUITE = "real-nav2-heldout"
# Issue 20's blind sets (evals/data/real_nav2/blind.yaml, blind2.yaml, ...): real-nav2-blind, real-nav2-blind2, ...
BLIND_SUITE = "real-nav2-blind"
SUITES: dict[str, tuple[str, Callable[[], tuple[Excerpt, ...]]]] = {
    SUITE: ("corpus.yaml", corpus), HELDOUT_SUITE: ("heldout.yaml", heldout),
    **{BLIND_SUITE + (str(n) if n > 1 else ""): (name, partial(blind_set, n))
       for n, name in enumerate(BLIND_FILES, start=1)}}
NO_PROGRESS = "navigation.no_progress"
UNEXPLAINED = "navigation.unexplained_failure"
HONEST_CAUSES = frozenset({NO_PROGRESS, UNEXPLAINED})
# True of any run that moved; never an unsupported claim (as in evals/graders.py).
NEVER_FALSE = frozenset({"navigation.nominal_speed"})
HONEST_WORDS = re.compile(
    r"\b(logs?|lines?|recording)\b[^.]{0,40}\b(do(es)?n[o']t|do(es)? not|never) (show|say|tell|explain)|"
    r"nothing in (my|the) (navigation )?logs? (says|shows|explains)|(not|n't) (have )?enough information|"
    r"(can(no|')t|could ?n[o']t) tell (why|what)", re.I)
QUESTIONS = {"failed": "Why didn't you get there?", "succeeded": "How did the navigation go?",
             "slow": "Why did it take so long to get there?"}


def implied(cause: str) -> frozenset[str]:
    known = vocabulary().get(cause)
    return frozenset(known.implies) if known is not None else frozenset()


def refinements(cause: str) -> frozenset[str]:
    """Causes that imply `cause`: the same cause told in more detail (a node that never came up is the stack "not
    brought up" of configuration_error), never a different one; an honest label ("nothing says why") has none."""
    if cause in HONEST_CAUSES:
        return frozenset()
    return frozenset(c for c, known in vocabulary().items() if cause in known.implies)


def unsupported(excerpt: Excerpt, claims: Iterable[str]) -> list[str]:
    allowed = {excerpt.cause, *implied(excerpt.cause), *refinements(excerpt.cause), *HONEST_CAUSES, *NEVER_FALSE}
    out = []
    for c in claims:
        if c == ALL_FINE:
            wrong = excerpt.outcome == "failed"
        elif c == TASK_FAILED:
            wrong = excerpt.outcome != "failed"
        else:
            wrong = c.startswith("navigation.") or c in vocabulary()
            wrong = wrong and c not in allowed
        if wrong:
            out.append(c)
    return sorted(out)


@dataclass(frozen=True)
class Grade:
    named: bool
    honest: bool
    unsupported: tuple[str, ...]
    verdict: str  # named | honest | wrong


def grade(excerpt: Excerpt, claims: Iterable[str], text: str = "") -> Grade:
    claims = set(claims)
    bad = tuple(unsupported(excerpt, claims))
    named = excerpt.cause in claims
    honest = not bad and (bool(claims & HONEST_CAUSES) or bool(HONEST_WORDS.search(text)))
    if bad:
        verdict = "wrong"
    elif named and excerpt.cause not in HONEST_CAUSES:
        verdict = "named"
    elif honest or named:
        verdict = "honest"
    else:
        verdict = "wrong"
    return Grade(named, honest, bad, verdict)


@dataclass(frozen=True)
class Result:
    id: str
    distro: str
    cause: str
    outcome: str
    logs_show_cause: bool
    with_task: bool
    question: str
    answer: str
    error: str
    causes: tuple[str, ...]
    claims: tuple[str, ...]
    text: Grade
    structured: Grade

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)


Ask = Callable[[Path, str], dict[str, Any]]


def hexar_asker(backend: Backend) -> Ask:
    from hexar.agent.context import RunSettings
    from hexar.agent.session import Session

    def ask(recording: Path, question: str) -> dict[str, Any]:
        session = Session(RunSettings(recording=recording, llm=backend.name), backend=backend)
        return session.ask(question)

    return ask


def evaluate(excerpts: Sequence[Excerpt], runs: Path, ask: Ask, step: Callable[[str], None] | None = None
             ) -> list[Result]:
    """Writes every excerpt as a recording under `runs` (replacing an older one) and grades HEXAR's answer."""
    import shutil

    out: list[Result] = []
    for ex, task in zip(excerpts, task_plan(excerpts), strict=True):
        path = runs / ex.id
        if path.exists():
            shutil.rmtree(path)
        write_recording(ex, path, task)
        question = QUESTIONS[ex.outcome]
        try:
            r = ask(path, question)
            answer, error, causes = str(r.get("answer", "")), str(r.get("error", "")), tuple(r.get("causes", ()))
        except USER_ERRORS as err:  # e.g. no task to explain: that excerpt is answered by nothing
            # the recording's temporary folder is no part of the result: name the excerpt instead
            answer, error, causes = "", f"{type(err).__name__}: {err}".replace(str(path), ex.id), ()
        claims = tuple(sorted(read_claims(answer).affirmed))
        out.append(Result(ex.id, ex.distro, ex.cause, ex.outcome, ex.logs_show_cause, task, question, answer,
                          error, causes, claims, grade(ex, claims, answer), grade(ex, causes)))
        if step is not None:
            step(ex.id)
    return out


def summarise(results: Sequence[Result], key: Callable[[Result], str] | None = None) -> dict[str, dict[str, Any]]:
    """Per group (all excerpts when `key` is None): counts and rates of the three metrics, text and structured."""
    groups: dict[str, list[Result]] = {}
    for r in results:
        groups.setdefault(key(r) if key else "all", []).append(r)
    out: dict[str, dict[str, Any]] = {}
    for name, rs in groups.items():
        shown = [r for r in rs if r.logs_show_cause and r.cause not in HONEST_CAUSES]
        row: dict[str, Any] = {"n": len(rs), "n_shown": len(shown)}
        for kind in ("text", "structured"):
            g = [getattr(r, kind) for r in rs]
            named = sum(getattr(r, kind).named for r in shown)
            row[kind] = {
                "named": named, "named_rate": named / len(shown) if shown else None,
                "no_unsupported": sum(not x.unsupported for x in g),
                "no_unsupported_rate": sum(not x.unsupported for x in g) / len(g),
                "honest": sum(x.verdict == "honest" for x in g),
                "wrong": sum(x.verdict == "wrong" for x in g),
            }
        out[name] = row
    return out


def by_distro(results: Sequence[Result]) -> dict[str, dict[str, Any]]:
    rows = summarise(results, key=lambda r: r.distro)
    return {d: rows[d] for d in DISTROS if d in rows}


def build_report(results: Sequence[Result], backend: str, excerpts: Sequence[Excerpt], suite: str = SUITE,
                 cases: Path | None = None) -> dict[str, Any]:
    sources = sorted({e.source for e in excerpts})
    data: dict[str, Any] = {"data": str(cases), "cases": True} if cases is not None else {"data": SUITES[suite][0]}
    scripts = {source.split(" on ")[0] for source in sources}
    if cases is None and len(scripts) == 1 and next(iter(scripts)).startswith("scripts/"):
        data["made_by"] = scripts.pop()  # a set the project's own script ran on the real stack, not pasted threads
    return {
        "suite": suite, **data, "backend": backend, "n": len(results), "sources": len(sources),
        "summary": summarise(results)["all"], "by_distro": by_distro(results),
        "by_cause": dict(sorted(summarise(results, key=lambda r: r.cause).items())),
        "excerpts": [r.as_dict() for r in results],
    }


def run_suite(backend: Backend, runs: Path | None = None, ask: Ask | None = None,
              step: Callable[[str], None] | None = None,
              excerpts: Sequence[Excerpt] | None = None, suite: str = SUITE, cases: Path | None = None
              ) -> dict[str, Any]:
    """`cases`: a file of the user's own excerpts in the corpus's format, run instead of the suite's data."""
    if excerpts is None:
        excerpts = read_cases(cases) if cases is not None else SUITES[suite][1]()
    ask = ask or hexar_asker(backend)
    if runs is None:
        with tempfile.TemporaryDirectory(prefix="hexar-real-nav2-") as tmp:
            return build_report(evaluate(excerpts, Path(tmp), ask, step), backend.name, excerpts, suite, cases)
    runs.mkdir(parents=True, exist_ok=True)
    return build_report(evaluate(excerpts, runs, ask, step), backend.name, excerpts, suite, cases)
