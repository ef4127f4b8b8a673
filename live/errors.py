"""Errors of the live node, the replayer and the transports."""

from __future__ import annotations

from hexar.errors import HexarError


class LiveError(HexarError):
    """Base class of the live package's user-facing errors."""


class TransportUnavailableError(LiveError):
    """The asked-for transport cannot run here (no cyclonedds binding, or no ROS 2 install for rclpy)."""


class BadOptionError(LiveError):
    """An option of `hexar serve` / `hexar replay` has a value that cannot work."""
