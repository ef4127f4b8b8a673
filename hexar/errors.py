"""Errors every HEXAR command reports as one line."""

from __future__ import annotations

from hexar.events.errors import EventsError
from hexar.explainers.errors import ExplainerError


class HexarError(Exception):
    """A user-facing error outside the event log and the explainers (bad question, bad option)."""


USER_ERRORS: tuple[type[Exception], ...] = (HexarError, EventsError, ExplainerError)


class InputFileError(HexarError):
    """A file or folder argument that is missing, of the wrong kind, unreadable, binary or wrongly encoded."""


class BadJsonError(HexarError):
    """JSON from outside (a recording, a topic, a request) that is malformed, too large or nested too deep."""
