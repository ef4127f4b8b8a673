"""HEXAR: hierarchical explainability for modular robots."""

from __future__ import annotations

__version__ = "0.1.0"
