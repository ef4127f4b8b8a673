"""An added explainer's tool description (agent router and `hexar mcp`): its `description` attribute when it has
one, else its class docstring, as the README says."""

from __future__ import annotations

from pathlib import Path
from typing import ClassVar

from hexar.events import contract as c
from hexar.explainers.base import Context, Explanation
from hexar.explainers.registry import Registry
from hexar.tools.explainer_tools import tools_for
from tests.explainers.test_registry import DiagnosticsExplainer


class BatteryExplainer:
    """Battery and docking: whether the robot was charging, from the recorded charging flag.

    Answers "why didn't you move?" when the robot stayed on its dock."""

    name: ClassVar[str] = "battery"
    topics: ClassVar[frozenset[str]] = frozenset({c.IS_CHARGING})

    def __init__(self, model: object = None, registry: object = None) -> None:
        self.model = model

    def explain(self, question: str, context: Context) -> Explanation:
        return Explanation.not_enough(self.name, "I have no battery explanation for this run.")


class QuietDiagnostics(DiagnosticsExplainer):
    """Inherits the description attribute; this docstring must not replace it."""


class Undocumented:
    name: ClassVar[str] = "undocumented"
    topics: ClassVar[frozenset[str]] = frozenset({c.ROSOUT})


def _registry(tmp_path: Path) -> Registry:
    cfg = tmp_path / "modules.toml"
    here = "tests.explainers.test_registry_descriptions"
    cfg.write_text(f'[explainers]\nbattery = "{here}:BatteryExplainer"\nquiet = "{here}:QuietDiagnostics"\n'
                   f'diagnostics = "tests.explainers.test_registry:DiagnosticsExplainer"\n'
                   f'undocumented = "{here}:Undocumented"\n[modules]\ndock = ["battery"]\n')
    return Registry.load(config=cfg)


def test_docstring_is_the_description_when_there_is_no_attribute(tmp_path: Path) -> None:
    registry = _registry(tmp_path)
    described = registry.descriptions()
    assert described["battery"] == ("Battery and docking: whether the robot was charging, from the recorded "
                                    "charging flag.\n\nAnswers \"why didn't you move?\" when the robot stayed on "
                                    "its dock.")
    tools = {t.name: t.description for t in tools_for(registry)}
    assert "Battery and docking" in tools["explain_battery"]


def test_a_description_attribute_wins_and_nothing_is_borrowed(tmp_path: Path) -> None:
    described = _registry(tmp_path).descriptions()
    assert described["diagnostics"] == DiagnosticsExplainer.description
    assert described["quiet"] == DiagnosticsExplainer.description  # inherited attribute, not the new docstring
    assert described["undocumented"] == ""  # no base class's or object's docstring stands in
