"""Errors of the component explainers."""

from __future__ import annotations


class ExplainerError(Exception):
    """Base class of every explainer error."""


class UnknownExplainerError(ExplainerError):
    """No explainer is registered under that name."""


class RegistryConfigError(ExplainerError):
    """The module-to-explainer mapping is malformed or names a missing explainer."""


class ModelError(ExplainerError):
    """A language model is missing, unreachable, or answered with something unusable."""
