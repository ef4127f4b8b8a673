"""The cause vocabulary shared by the faithfulness guard and the eval graders."""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from importlib import resources

import yaml


@dataclass(frozen=True)
class Cause:
    id: str
    means: str
    patterns: tuple[re.Pattern[str], ...]
    implies: tuple[str, ...] = ()

    @property
    def module(self) -> str:
        return self.id.split(".", 1)[0]

    def stated_in(self, text: str) -> bool:
        return any(p.search(text) for p in self.patterns)


@cache
def vocabulary() -> dict[str, Cause]:
    raw = yaml.safe_load(resources.files("hexar").joinpath("causes.yaml").read_text(encoding="utf-8"))
    return {
        cid: Cause(cid, entry["means"], tuple(re.compile(p, re.I) for p in entry["patterns"]),
                   tuple(entry.get("implies", ())))
        for cid, entry in raw.items()
    }


def stated_causes(text: str) -> set[str]:
    """Every known cause whose phrasing appears in `text`."""
    return {cid for cid, cause in vocabulary().items() if cause.stated_in(text)}
