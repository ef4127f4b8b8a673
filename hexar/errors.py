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


class LinkOutsideError(HexarError):
    """A served recording that is, or holds, a symlink to a file outside the served folder."""


class McpOptionError(HexarError):
    """`hexar mcp` options that would expose the recordings: HTTP off loopback without a token."""


class BadOptionValueError(HexarError):
    """A number option out of its range: a port above 65535, a scenario the paper does not have."""
