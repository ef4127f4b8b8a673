"""Prompt texts, kept as files so that a change to one shows in review and in the eval report's hashes."""

from __future__ import annotations

import hashlib
from importlib import resources


def load(name: str) -> str:
    """The text of `prompts/<name>.md`."""
    return resources.files("hexar.prompts").joinpath(f"{name}.md").read_text(encoding="utf-8")


def hashes() -> dict[str, str]:
    """sha256 (first 12 hex digits) of every prompt file, for eval reports."""
    out = {}
    for entry in sorted(resources.files("hexar.prompts").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".md"):
            out[entry.name] = hashlib.sha256(entry.read_bytes()).hexdigest()[:12]
    return out
