"""The registry of component explainers and the module mapping M, both configuration rather than code."""

from __future__ import annotations

import importlib
import inspect
import tomllib
from collections.abc import Iterable, Iterator, Mapping
from functools import cache
from importlib import resources
from importlib.metadata import entry_points
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

from hexar.explainers.base import Explainer, TextModel
from hexar.explainers.errors import RegistryConfigError, UnknownExplainerError

if TYPE_CHECKING:
    from hexar.events.tasks import Task

ENTRY_POINT_GROUP = "hexar.explainers"
PLANNER = "planner"


def _load_class(ref: str) -> type[Any]:
    module_name, _, attr = ref.partition(":")
    if not attr:
        raise RegistryConfigError(f"explainer reference {ref!r} must look like 'package.module:Class'")
    try:
        return getattr(importlib.import_module(module_name), attr)  # type: ignore[no-any-return]
    except (ImportError, AttributeError) as err:
        raise RegistryConfigError(f"cannot load explainer {ref!r}: {err}") from err


class _EntryPoint(Protocol):
    name: str

    def load(self) -> Any: ...


class Classes(Mapping[str, type[Any]]):
    """Explainer classes by name; one given as an entry point is imported when it is first asked for, so a
    question one explainer answers does not import the others (each brings its catalogue)."""

    def __init__(self, given: Mapping[str, type[Any] | _EntryPoint]) -> None:
        self._given = dict(given)

    def __getitem__(self, name: str) -> type[Any]:
        value = self._given[name]
        if isinstance(value, type):
            return value
        try:
            cls = value.load()
        except (ImportError, AttributeError) as err:
            raise RegistryConfigError(f"entry point {name!r} cannot be loaded: {err}") from err
        if not isinstance(cls, type):
            raise RegistryConfigError(f"entry point {name!r} is not a class")
        self._given[name] = cls
        return cls

    def __contains__(self, name: object) -> bool:
        return name in self._given  # without importing it

    def __iter__(self) -> Iterator[str]:
        return iter(self._given)

    def __len__(self) -> int:
        return len(self._given)


@cache
def _entry_points() -> dict[str, _EntryPoint]:
    # Scanning every installed distribution's entry points costs milliseconds; a batch over many recordings
    # loads a registry per recording, and the installed set does not change while it runs.
    return {ep.name: ep for ep in entry_points(group=ENTRY_POINT_GROUP)}


def read_config(path: Path | None = None) -> dict[str, Any]:
    """The mapping file: the packaged `modules.toml`, or the one at `path`."""
    from hexar.errors import InputFileError
    from hexar.inputs import read_text_arg

    try:
        if path is None:
            text = resources.files("hexar.explainers").joinpath("modules.toml").read_text()
        else:
            text = read_text_arg(Path(path), "explainer config")
        return tomllib.loads(text)
    except InputFileError as err:
        raise RegistryConfigError(str(err)) from err
    except (OSError, tomllib.TOMLDecodeError) as err:
        raise RegistryConfigError(f"cannot read explainer config {path}: {err}") from err


class Registry:
    """Explainer classes by name, their instances (created on first use), and the module mapping."""

    def __init__(
        self,
        classes: Mapping[str, type[Any] | _EntryPoint],
        modules: Mapping[str, Iterable[str]],
        model: TextModel | None = None,
    ) -> None:
        self.classes = Classes(classes)
        self.modules = {skill: list(names) for skill, names in modules.items()}
        self.model = model
        self._instances: dict[str, Explainer] = {}
        for skill, names in self.modules.items():
            for name in names:
                if name not in self.classes:
                    raise RegistryConfigError(f"module {skill!r} maps to unknown explainer {name!r}")

    @classmethod
    def load(cls, model: TextModel | None = None, config: Path | None = None) -> Registry:
        """Entry points of the `hexar.explainers` group, then the config's own [explainers] and [modules]."""
        classes: dict[str, type[Any] | _EntryPoint] = dict(_entry_points())
        data = read_config(None)
        if config is not None:
            extra = read_config(config)
            data = {
                "modules": {**data.get("modules", {}), **extra.get("modules", {})},
                "explainers": {**data.get("explainers", {}), **extra.get("explainers", {})},
            }
        for name, ref in (data.get("explainers") or {}).items():
            classes[name] = _load_class(str(ref))
        return cls(classes, data.get("modules") or {}, model)

    @property
    def names(self) -> list[str]:
        return sorted(self.classes)

    def get(self, name: str) -> Explainer:
        if name not in self.classes:
            raise UnknownExplainerError(f"no explainer named {name!r} (known: {', '.join(self.names)})")
        if name not in self._instances:
            self._instances[name] = self.classes[name](model=self.model, registry=self)
        return self._instances[name]

    def for_module(self, skill: str) -> list[str]:
        """Explainers of a robot module; a skill the robot does not have is the planner's to explain."""
        return self.modules.get(skill) or [PLANNER]

    def failure_explainer(self, task: Task) -> str | None:
        """The deterministic failure check, shared by the agent and fleet triage: a bad plan goes to the planner,
        a failed skill to its module's first explainer, a plan that does not fulfil the request to the planner;
        None when nothing failed."""
        from hexar.explainers.planner import task_findings

        if not task.valid:
            return PLANNER
        if (failed := task.failed_skill) is not None:
            return self.for_module(failed.skill)[0]
        return PLANNER if task_findings(task) else None

    def descriptions(self) -> dict[str, str]:
        """What each explainer explains, for the agent's router and the MCP tools: its `description` attribute,
        else its class docstring (an added explainer is often documented only there)."""
        return {name: describe(self.classes[name]) for name in self.names}


def describe(cls: type[Any]) -> str:
    given = getattr(cls, "description", None)
    if isinstance(given, str) and given.strip():
        return given
    # the class's own docstring only: __doc__ is not inherited, so a base class's text never stands in
    own = cls.__dict__.get("__doc__")
    return inspect.cleandoc(own) if isinstance(own, str) else ""
