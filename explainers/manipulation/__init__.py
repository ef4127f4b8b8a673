"""Manipulation (MoveIt 2) component explainer."""

from __future__ import annotations

from hexar.explainers.manipulation.explainer import ManipulationExplainer

__all__ = ["ManipulationExplainer"]
