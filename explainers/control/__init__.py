"""Control (ros2_control) component explainer."""

from __future__ import annotations

from hexar.explainers.control.explainer import ControlExplainer

__all__ = ["ControlExplainer"]
