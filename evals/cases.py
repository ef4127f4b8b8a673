"""The eval cases: 20 scenarios x 3 instruction variants x 3 questions, from `evals/data/scenarios.yaml`."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache
from importlib import resources
from typing import Any, Literal

import yaml

QuestionKind = Literal["generic", "task", "observed"]
KINDS: tuple[QuestionKind, ...] = ("generic", "task", "observed")


@dataclass(frozen=True)
class Variant:
    key: str
    instruction: str
    object: str
    room: str
    home: str


@dataclass(frozen=True)
class Scenario:
    id: int
    category: str
    module: str
    explainer: str
    cause: str
    also: tuple[str, ...]
    root_cause: str
    variants: tuple[Variant, ...]
    questions: tuple[str, str, str]


@dataclass(frozen=True)
class Case:
    """One graded question about one recording."""

    id: str
    recording: str
    scenario: Scenario
    variant: int
    kind: QuestionKind
    question: str


@cache
def _data() -> dict[str, Any]:
    text = resources.files("hexar.evals").joinpath("data/scenarios.yaml").read_text(encoding="utf-8")
    data: dict[str, Any] = yaml.safe_load(text)
    return data


@cache
def scenarios() -> tuple[Scenario, ...]:
    data = _data()
    variants = {key: Variant(key=key, **value) for key, value in data["variants"].items()}
    out = []
    for s in data["scenarios"]:
        out.append(
            Scenario(
                id=int(s["id"]), category=s["category"], module=s["module"], explainer=s["explainer"],
                cause=s["cause"], also=tuple(s.get("also", ())), root_cause=s["root_cause"],
                variants=tuple(variants[v] for v in s["variants"]),
                questions=(s["questions"][0], s["questions"][1], s["questions"][2]),
            )
        )
    return tuple(out)


def scenario(sid: int) -> Scenario:
    for s in scenarios():
        if s.id == sid:
            return s
    raise KeyError(f"no scenario {sid}")


def recording_name(sid: int, variant: int) -> str:
    """The original release's naming: bagfile_<scenario>_<repetition>."""
    return f"bagfile_{sid}_{variant}"


def cases() -> list[Case]:
    out = []
    for s in scenarios():
        for vi, variant in enumerate(s.variants, start=1):
            for kind, template in zip(KINDS, s.questions, strict=True):
                out.append(
                    Case(
                        id=f"{s.id}.{vi}.{kind}",
                        recording=recording_name(s.id, vi),
                        scenario=s,
                        variant=vi,
                        kind=kind,
                        question=template.format(object=variant.object),
                    )
                )
    return out
