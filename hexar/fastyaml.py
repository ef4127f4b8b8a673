"""YAML read with libyaml's parser where PyYAML has it (its wheels do): the same data as `yaml.safe_load`, without
a pure-Python parse of the project's own files and recordings' metadata on every cold start."""

from __future__ import annotations

from typing import Any

import yaml

LIBYAML = hasattr(yaml, "CSafeLoader")
LOADER: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def load(text: str) -> Any:
    """`text` as `yaml.safe_load` reads it."""
    return yaml.load(text, Loader=LOADER)
