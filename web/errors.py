"""Errors of the figure, annotation and page commands, each reported as one line."""

from __future__ import annotations

from hexar.errors import HexarError


class WebError(HexarError):
    """A user-facing error of `--plot`, `hexar annotate` or `hexar web`."""


class PlotError(WebError):
    """The figure cannot be written (bad output path)."""


class AnnotateError(WebError):
    """The recording cannot be annotated (unsupported format, bad output path)."""
