"""Errors of the agent."""

from __future__ import annotations

from hexar.errors import HexarError


class AgentError(HexarError):
    """Base class of agent errors."""


class BadQuestionError(AgentError):
    """The question is empty, gibberish, or not a question."""


class BackendError(AgentError):
    """The requested LLM backend is unknown, missing or unreachable."""
