"""JSON from outside read with limits: deep nesting and huge texts refused with one line that quotes nothing."""

from __future__ import annotations

import pytest

from hexar.bounded_json import MAX_DEPTH, loads
from hexar.errors import BadJsonError
from hexar.events.task_info import parse_task_info


@pytest.mark.parametrize("text", ["[" * 2000 + "]" * 2000, '{"a":' * 5000 + "1" + "}" * 5000,
                                  "[" * (MAX_DEPTH + 1) + "]" * (MAX_DEPTH + 1), '"' + "x" * 2_000_000 + '"',
                                  b"[" * (MAX_DEPTH + 1) + b"]" * (MAX_DEPTH + 1),
                                  '{"a": "' + "{" * 40 + '", "b": ' + "[" * 40 + "]" * 40 + "}",
                                  '{"secret": 1', b"\xff\xfe"])
def test_refused_with_one_line_that_quotes_nothing(text: str | bytes) -> None:
    with pytest.raises(BadJsonError) as refused:
        loads(text)
    message = str(refused.value)
    assert "\n" not in message and len(message) < 120 and "secret" not in message and "xxx" not in message


def test_ordinary_json_is_read() -> None:
    assert loads('{"task_id": "t1", "skill_sequence": [{"params": {"zone": [1, 2]}}]}')["task_id"] == "t1"
    assert loads("[" * MAX_DEPTH + "]" * MAX_DEPTH) is not None
    assert loads(b"[" * MAX_DEPTH + b"]" * MAX_DEPTH) is not None
    assert loads('{"a": "' + "[" * 100 + '"}') == {"a": "[" * 100}  # brackets in a string nest nothing


def test_a_task_update_too_deep_to_read_is_no_task_update() -> None:
    deep_params = '{"task_id": "t", "skill_sequence": [{"skill": "say", "params": ' + "[" * 900 + "]" * 900 + "}]}"
    assert parse_task_info(0, deep_params) is None
    assert parse_task_info(0, "[" * 2000 + "]" * 2000) is None
    update = parse_task_info(0, '{"task_id": "t", "skill_sequence": [{"skill": "say", "params": {"a": [[1]]}}]}')
    assert update is not None and update.skills[0].params == {"a": [[1]]}
