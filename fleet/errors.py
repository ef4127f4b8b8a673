"""Errors of fleet triage."""

from __future__ import annotations

from hexar.errors import HexarError


class TriageError(HexarError):
    """Bad triage input: nothing to triage, a bad option, an unreadable results folder."""
