"""The hand decoders of /diagnostics-style DiagnosticArray and std_msgs/Bool read what rosbags reads from the same
bytes, and leave to rosbags (None) or refuse (LayoutError) what is not the standard layout."""

from __future__ import annotations

import numpy as np
import pytest
from rosbags.serde import SerdeError

from hexar.evals.scenarios.bag import TYPESTORE
from hexar.events.cdr import LayoutError, decode_bool, decode_diagnostics
from hexar.events.decode import diag_fields

TY = TYPESTORE.types
DIAG = "diagnostic_msgs/msg/DiagnosticArray"
WORDS = ["", "a", "ab", "abc", "abcd", "battery", "Señal ✓", "/move_base/planner", "x" * 37, "HW-01"]


def _array(rng: np.random.Generator) -> object:
    """A DiagnosticArray of random shape: string lengths hit every alignment, sequences may be empty."""
    def word() -> str:
        return str(WORDS[int(rng.integers(len(WORDS)))])

    statuses = [
        TY["diagnostic_msgs/msg/DiagnosticStatus"](
            level=int(rng.choice([0, 1, 2, 3, 127, -128])), name=word(), message=word(), hardware_id=word(),
            values=[TY["diagnostic_msgs/msg/KeyValue"](key=word(), value=word())
                    for _ in range(int(rng.integers(4)))])
        for _ in range(int(rng.integers(4)))
    ]
    stamp = TY["builtin_interfaces/msg/Time"](sec=int(rng.integers(2**31)), nanosec=int(rng.integers(10**9)))
    return TY[DIAG](header=TY["std_msgs/msg/Header"](stamp=stamp, frame_id=word()), status=statuses)


def test_diagnostics_decoded_by_hand_equal_rosbags_own() -> None:
    rng = np.random.default_rng(7)
    for _ in range(300):
        raw = bytes(TYPESTORE.serialize_cdr(_array(rng), DIAG))
        assert decode_diagnostics(raw) == diag_fields(TYPESTORE.deserialize_cdr(raw, DIAG))


def test_a_repeated_array_keeps_its_own_stamp_and_a_changed_one_its_own_statuses() -> None:
    # decoded statuses are kept by the bytes after the stamp: the stamp and any change after it must still show
    rng = np.random.default_rng(11)
    for _ in range(100):
        msg = _array(rng)
        first = bytes(TYPESTORE.serialize_cdr(msg, DIAG))
        msg.header.stamp.sec += 1  # type: ignore[attr-defined]
        again = bytes(TYPESTORE.serialize_cdr(msg, DIAG))
        for raw in (first, again):
            assert decode_diagnostics(raw) == diag_fields(TYPESTORE.deserialize_cdr(raw, DIAG))
    level = TY["diagnostic_msgs/msg/DiagnosticStatus"](level=0, name="battery", message="ok", hardware_id="",
                                                        values=[TY["diagnostic_msgs/msg/KeyValue"](key="v", value="1")])
    stamp = TY["builtin_interfaces/msg/Time"](sec=1, nanosec=2)
    arr = TY[DIAG](header=TY["std_msgs/msg/Header"](stamp=stamp, frame_id="f"), status=[level])
    before = decode_diagnostics(bytes(TYPESTORE.serialize_cdr(arr, DIAG)))
    level.values[0].value = "2"
    after = decode_diagnostics(bytes(TYPESTORE.serialize_cdr(arr, DIAG)))
    assert before is not None and after is not None
    assert before[2][0][4] == (("v", "1"),) and after[2][0][4] == (("v", "2"),)


def test_diagnostics_rosbags_cannot_decode_are_left_to_it() -> None:
    status = TY["diagnostic_msgs/msg/DiagnosticStatus"](level=2, name="ab", message="cd", hardware_id="",
                                                         values=[])
    stamp = TY["builtin_interfaces/msg/Time"](sec=1, nanosec=2)
    raw = bytearray(TYPESTORE.serialize_cdr(TY[DIAG](header=TY["std_msgs/msg/Header"](stamp=stamp, frame_id="f"),
                                                        status=[status]), DIAG))
    bad = bytes(raw).replace(b"cd\x00", b"c\xff\x00")  # not UTF-8: rosbags raises, so the reader gets its error
    with pytest.raises(SerdeError, match="utf-8"):
        TYPESTORE.deserialize_cdr(bad, DIAG)
    assert decode_diagnostics(bad) is None
    assert decode_diagnostics(bytes([0, 0, 0, 0]) + bytes(raw[4:])) is None  # big-endian flag
    assert decode_diagnostics(bytes(raw[:-6])) is None  # cut short
    with pytest.raises(LayoutError):  # bytes the standard layout does not have: another definition
        decode_diagnostics(bytes(raw) + bytes(16))


@pytest.mark.parametrize("value", [True, False])
def test_bool_decoded_by_hand_equals_rosbags_own(value: bool) -> None:
    raw = bytes(TYPESTORE.serialize_cdr(TY["std_msgs/msg/Bool"](data=value), "std_msgs/msg/Bool"))
    assert decode_bool(raw) is bool(TYPESTORE.deserialize_cdr(raw, "std_msgs/msg/Bool").data) is value
    odd = raw[:4] + b"\x02" + raw[5:]  # any non-zero byte is true to rosbags too
    assert decode_bool(odd) is bool(TYPESTORE.deserialize_cdr(odd, "std_msgs/msg/Bool").data) is True
    assert decode_bool(raw[:4]) is None
    with pytest.raises(LayoutError):
        decode_bool(raw + bytes(12))
