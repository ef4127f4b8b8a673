"""Errors of the stack catalogue."""

from __future__ import annotations

from hexar.explainers.errors import ExplainerError


class StackCatalogueError(ExplainerError):
    """stack_catalogue.json (or a catalogue given to the loader) is malformed."""
