"""The DDS wire types (live/msgs.py) are the ROS 2 IDL of each message, field for field, checked against the
message classes rosidl generated for the Kilted rclpy wheels: `byte` is an octet, `float64[36]` a fixed array,
`T[]` an unbounded sequence. A type that differs in one field kind does not match a Fast DDS or Connext peer."""

from __future__ import annotations

import importlib
import typing
from typing import Any

import pytest

# cyclonedds has no wheel for CPython 3.14 (the lock installs it only below); these tests are of the DDS transport
pytest.importorskip("cyclonedds", reason="cyclonedds (the `live` extra) has no wheel for this Python")

from hexar.live import msgs
from hexar.live.dds import IDL
from hexar.live.ros import ROS_TYPES

pytest.importorskip("rclpy")
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import array, sequence

# the names cyclonedds uses for primitive kinds, as rosidl writes them
PRIMITIVE = {"byte": "octet", "float32": "float", "float64": "double", "int8": "int8", "uint8": "uint8",
             "int32": "int32", "uint32": "uint32", "int64": "int64"}


def ros_name(cls: type[Any]) -> str:
    """`std_msgs::msg::dds_::Header_` -> `std_msgs/Header`, rosidl's spelling of a nested type."""
    pkg, _, _, name = cls.__idl_typename__.split("::")
    return f"{pkg}/{name[:-1]}"


def rosidl(hint: Any) -> str:
    if hint is str:
        return "string"
    if hint is bool:
        return "boolean"
    if isinstance(hint, type) and issubclass(hint, IdlStruct):
        return ros_name(hint)
    meta = hint.__metadata__[0]
    if isinstance(meta, str):
        return PRIMITIVE[meta]
    if isinstance(meta, array):
        return f"{rosidl(meta.subtype)}[{meta.length}]"
    assert isinstance(meta, sequence) and meta.max_length is None
    return f"sequence<{rosidl(meta.subtype)}>"


def nested(cls: type[Any]) -> list[type[Any]]:
    """`cls` and every struct it contains, depth first."""
    out = [cls]
    for hint in typing.get_type_hints(cls, include_extras=True).values():
        inner = hint
        if hasattr(hint, "__metadata__") and isinstance(hint.__metadata__[0], (array, sequence)):
            inner = hint.__metadata__[0].subtype
        if isinstance(inner, type) and issubclass(inner, IdlStruct):
            out += [c for c in nested(inner) if c not in out]
    return out


def rclpy_class(cls: type[Any]) -> Any:
    pkg, _, _, name = cls.__idl_typename__.split("::")
    return getattr(importlib.import_module(f"{pkg}.msg"), name[:-1])


@pytest.mark.parametrize("ros_type", sorted(IDL))
def test_each_wire_type_is_the_ros_idl(ros_type: str) -> None:
    for cls in nested(IDL[ros_type]):
        ours = {name: rosidl(hint) for name, hint in typing.get_type_hints(cls, include_extras=True).items()}
        assert ours == rclpy_class(cls).get_fields_and_field_types(), cls.__idl_typename__


def test_every_transport_type_has_a_wire_type() -> None:
    assert set(IDL) == set(ROS_TYPES)
    assert typing.get_type_hints(msgs.DiagnosticStatus, include_extras=True)["level"].__metadata__[0] == "byte"
