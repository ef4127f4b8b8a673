"""JSON that somebody else wrote (a recording's /task_info, an answer on /hexar/answer, a question, a request
body) read with limits: a size cap and a nesting cap, and a refusal instead of a RecursionError.

The standard library's parser recurses once per bracket, so 2,000 nested `[` end in RecursionError in the
parser or, if the parser copes, in whatever walks the result next (NaN checks, rendering, JSON output).
"""

from __future__ import annotations

import json
from typing import Any

from hexar.errors import BadJsonError

MAX_DEPTH = 32
"""Deeper than any message HEXAR reads (a /task_info is 4 levels deep: task, skill_sequence, step, params)."""
MAX_CHARS = 1_000_000


def loads(text: str | bytes, max_chars: int = MAX_CHARS, max_depth: int = MAX_DEPTH) -> Any:
    """The JSON value of `text`, or BadJsonError (one line, never quoting the text)."""
    if len(text) > max_chars:
        raise BadJsonError(f"JSON of {len(text)} characters refused (at most {max_chars})")
    try:
        value = json.loads(text)
    except RecursionError as err:
        raise BadJsonError(f"JSON nested deeper than {max_depth} levels refused") from err
    except (json.JSONDecodeError, UnicodeDecodeError) as err:
        raise BadJsonError(f"not JSON: {type(err).__name__} at position {getattr(err, 'pos', '?')}") from err
    # a value nests no deeper than the text has opening brackets: most texts need no walk
    opening = text.count("[") + text.count("{") if isinstance(text, str) else text.count(b"[") + text.count(b"{")
    if opening > max_depth and depth_over(value, max_depth):
        raise BadJsonError(f"JSON nested deeper than {max_depth} levels refused")
    return value


def depth_over(value: Any, max_depth: int) -> bool:
    """True when `value` nests lists or dicts deeper than `max_depth` (walked without recursion)."""
    stack: list[tuple[Any, int]] = [(value, 1)]
    while stack:
        item, depth = stack.pop()
        children = item.values() if isinstance(item, dict) else item if isinstance(item, list) else None
        if children is None:
            continue
        if depth > max_depth:
            return True
        stack.extend((child, depth + 1) for child in children)
    return False
