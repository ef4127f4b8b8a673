"""YAML read with libyaml's parser where PyYAML has it (its wheels do): the same data as `yaml.safe_load`, without
a pure-Python parse of the project's own files and recordings' metadata on every cold start.

Even with libyaml, PyYAML builds a node for every value and runs its constructor over them in Python: two thirds
of reading a recording's metadata.yaml. A plain document (mappings, sequences and untagged scalars, no anchors,
aliases, tags or merge keys: what rosbag2 and the project write) is built here from libyaml's events instead, each
scalar resolved and constructed by PyYAML's own safe resolver and constructor, so the values are the same. Any
other document, and any error, goes to PyYAML's safe loader, which then reads it or raises its own error.
"""

from __future__ import annotations

from typing import Any

import yaml
from yaml.events import (
    DocumentEndEvent,
    DocumentStartEvent,
    MappingEndEvent,
    MappingStartEvent,
    ScalarEvent,
    SequenceEndEvent,
    SequenceStartEvent,
    StreamEndEvent,
    StreamStartEvent,
)
from yaml.nodes import ScalarNode

LIBYAML = hasattr(yaml, "CSafeLoader")
LOADER: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

_TAG = "tag:yaml.org,2002:"
# the scalar types the safe loader gives a plain document; any other resolved tag (merge keys, "=") is left to it
_PLAIN_TAGS = frozenset(_TAG + t for t in ("null", "bool", "int", "float", "str", "timestamp"))
_SCALARS_KEPT = 4096


class _Unusual(Exception):
    """Something this builder leaves to PyYAML: a tag, an anchor, a merge key, more than one document."""


class _Builder:
    """libyaml's events of a plain document, built into the values the safe loader gives."""

    def __init__(self) -> None:
        self._safe = yaml.SafeLoader("")  # its resolver and scalar constructors, nothing it parses
        self._resolve: Any = self._safe.resolve
        self._scalars: dict[tuple[str, bool], Any] = {}

    def scalar(self, event: ScalarEvent) -> Any:
        if event.anchor is not None or event.tag not in (None, "!"):
            raise _Unusual
        plain = bool(event.implicit[0])
        key = (event.value, plain)
        if (value := self._scalars.get(key, _MISSING)) is not _MISSING:
            return value
        tag = self._resolve(ScalarNode, event.value, (plain, not plain))
        if tag not in _PLAIN_TAGS:
            raise _Unusual
        value = self._safe.yaml_constructors[tag](self._safe, ScalarNode(tag, event.value))
        if len(self._scalars) >= _SCALARS_KEPT:
            self._scalars.clear()
        self._scalars[key] = value
        return value

    def build(self, text: str) -> Any:
        parser = yaml.CBaseLoader(text)
        try:
            events = iter(parser.get_event, None)
            if not isinstance(next(events), StreamStartEvent):
                raise _Unusual
            first = next(events)
            if isinstance(first, StreamEndEvent):
                return None
            if not isinstance(first, DocumentStartEvent):
                raise _Unusual
            value = self._node(next(events), events)
            if not isinstance(next(events), DocumentEndEvent) or not isinstance(next(events), StreamEndEvent):
                raise _Unusual
            return value
        finally:
            parser.dispose()

    def _node(self, event: Any, events: Any) -> Any:
        if isinstance(event, ScalarEvent):
            return self.scalar(event)
        if event.anchor is not None or event.tag not in (None, "!"):
            raise _Unusual
        if isinstance(event, SequenceStartEvent):
            items = []
            while not isinstance(item := next(events), SequenceEndEvent):
                items.append(self._node(item, events))
            return items
        if isinstance(event, MappingStartEvent):
            mapping: dict[Any, Any] = {}
            while not isinstance(key := next(events), MappingEndEvent):
                if not isinstance(key, ScalarEvent):
                    raise _Unusual  # a collection as a key: the safe loader's error
                k = self.scalar(key)
                mapping[k] = self._node(next(events), events)
            return mapping
        raise _Unusual  # an alias


_MISSING = object()
_BUILDER: _Builder | None = None


def load(text: str) -> Any:
    """`text` as `yaml.safe_load` reads it."""
    global _BUILDER
    if LIBYAML:
        if _BUILDER is None:
            _BUILDER = _Builder()
        try:
            return _BUILDER.build(text)
        except (_Unusual, yaml.YAMLError, StopIteration):
            pass
    return yaml.load(text, Loader=LOADER)
