"""Navigation (Nav2) component explainer."""

from __future__ import annotations

from hexar.explainers.navigation.explainer import NavigationExplainer

__all__ = ["NavigationExplainer"]
