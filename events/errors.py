"""Errors raised while reading a recording."""

from __future__ import annotations


class EventsError(Exception):
    """Base class of every error of the event log."""


class RecordingNotFoundError(EventsError):
    """The path does not exist."""


class NotARecordingError(EventsError):
    """The path exists but is no rosbag2 folder or ROS 1 bag."""


class CorruptRecordingError(EventsError):
    """The recording exists but cannot be read (truncated or damaged)."""


class UnknownMessageTypeError(EventsError):
    """A topic HEXAR needs carries a type it cannot decode."""


class EmptyRecordingError(EventsError):
    """The recording holds no messages."""


class NoTaskError(EventsError):
    """The recording holds no /task_info, or not the task asked for."""
