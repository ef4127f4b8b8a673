"""The mapping M is configuration: a sixth explainer joins through a config file, with no edit elsewhere."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import ClassVar

import pytest

from hexar.agent.context import RunSettings
from hexar.agent.session import Session
from hexar.events import contract as c
from hexar.explainers.base import Context, Evidence, Explanation, TextModel
from hexar.explainers.errors import RegistryConfigError, UnknownExplainerError
from hexar.explainers.navigation import NavigationExplainer
from hexar.explainers.registry import Registry
from hexar.tools.explainer_tools import tools_for


class DiagnosticsExplainer:
    """Reads /diagnostics only: a module the robot did not ship an explainer for."""

    name: ClassVar[str] = "diagnostics"
    topics: ClassVar[frozenset[str]] = frozenset({c.DIAGNOSTICS})
    description: ClassVar[str] = "Hardware diagnostics: the robot's 1 Hz node status reports and limits."

    def __init__(self, model: TextModel | None = None, registry: Registry | None = None) -> None:
        self.model = model

    def explain(self, question: str, context: Context) -> Explanation:
        records = context.view(self.topics).statuses(c.DIAGNOSTICS)
        if not records:
            return Explanation.not_enough(self.name, "No diagnostics were recorded then.")
        last = records[-1]
        k, v = last.data_items()[0]
        return Explanation(explainer=self.name, text=f"My last status report said {k} = {v}.",
                           causes=["diagnostics.report"],
                           evidence=[Evidence(cause="diagnostics.report", topic=c.DIAGNOSTICS, t=last.t,
                                              item=f"{k} = {v}")])


def _config(tmp_path: Path) -> Path:
    cfg = tmp_path / "modules.toml"
    cfg.write_text('[explainers]\ndiagnostics = "tests.explainers.test_registry:DiagnosticsExplainer"\n'
                   '[modules]\nnavigate_to_zone = ["navigation", "diagnostics"]\nself_check = ["diagnostics"]\n')
    return cfg


def test_entry_points_provide_the_five() -> None:
    assert set(Registry.load().names) >= {"planner", "navigation", "ask_human_for_help", "text_to_speech",
                                         "pizza_recommender"}


def test_a_sixth_explainer_from_config(tmp_path: Path, suite: Path) -> None:
    registry = Registry.load(config=_config(tmp_path))
    assert "diagnostics" in registry.names
    assert registry.for_module("navigate_to_zone") == ["navigation", "diagnostics"]  # several per module
    assert registry.for_module("self_check") == ["diagnostics"]
    assert registry.for_module("teleport") == ["planner"]  # a skill the robot lacks is a planning problem
    assert "explain_diagnostics" in {t.name for t in tools_for(registry)}
    settings = RunSettings(recording=suite / "bagfile_10_1", llm="none", registry_config=_config(tmp_path))
    result = Session(settings).ask("What else happened?")  # no history: a new question, routed by findings
    assert result["explainers"]
    session = Session(settings)
    first = session.ask("Why are you driving so slowly?")
    more = [session.ask("What else happened?", thread=first["thread"]) for _ in range(3)]
    assert "diagnostics" in {name for r in more for name in r["explainers"]}


def test_bad_config_is_a_clear_error(tmp_path: Path) -> None:
    bad = tmp_path / "bad.toml"
    bad.write_text('[modules]\nsay = ["nonexistent"]\n')
    with pytest.raises(RegistryConfigError, match="unknown explainer 'nonexistent'"):
        Registry.load(config=bad)
    broken = tmp_path / "broken.toml"
    broken.write_text('[explainers]\nx = "no.such.module:Thing"\n')
    with pytest.raises(RegistryConfigError, match="cannot load"):
        Registry.load(config=broken)
    with pytest.raises(UnknownExplainerError):
        Registry.load().get("nope")


def test_an_explainer_is_imported_when_it_is_first_asked_for() -> None:
    # a fresh interpreter: this test process has imported every explainer already
    code = ("import sys; from hexar.explainers.registry import Registry; r = Registry.load(); "
            "loaded = lambda: sorted(n for n in ('navigation', 'control', 'manipulation', 'pizza') "
            "if f'hexar.explainers.{n}' in sys.modules); "
            "before = loaded(); known = 'control' in r.classes and 'manipulation' in r.names; "
            "r.get('navigation'); print(before, known, loaded())")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[] True ['navigation']"


def test_an_entry_point_that_cannot_be_imported_is_a_clear_error_when_used() -> None:
    class Broken:
        name = "broken"

        def load(self) -> type:
            raise ImportError("No module named 'hexar_extra'")

    registry = Registry({"broken": Broken(), "navigation": NavigationExplainer}, {"self_check": ["broken"]})
    assert registry.for_module("self_check") == ["broken"] and "broken" in registry.names
    assert registry.get("navigation").name == "navigation"
    with pytest.raises(RegistryConfigError, match="entry point 'broken' cannot be loaded: No module named"):
        registry.get("broken")
