"""Which recordings the arguments of `hexar triage` name, and a label for each that is unique in the run and
starts at or above the recording's robot."""

from __future__ import annotations

import glob
import os
import re
from collections.abc import Iterable, Iterator
from pathlib import Path

from hexar.fleet.errors import TriageError
from hexar.workspace import find_recordings, is_recording

# A folder named by a date, with an optional time (2025-03-10, 2025-03-10_14-30, 2025-03-10T14:30:00Z): never a robot.
_DATE = re.compile(r"\d{4}-\d{2}-\d{2}(?:[T_ -]?\d{2}[-:_.]?\d{2}(?:[-:_.]?\d{2}(?:\.\d+)?)?(?:Z|[+-]\d{2}:?\d{2})?)?")


def is_date(name: str) -> bool:
    return _DATE.fullmatch(name) is not None


def robot_of(rel: str) -> str:
    """Fleets keep recordings as [FLEET/]ROBOT/[DATE/...]RECORDING: the first folder of the recording's label that
    is not a date (`expand` makes every label start at or above its robot)."""
    return next((part for part in rel.split("/")[:-1] if not is_date(part)), "")


def _matches(inputs: Iterable[str]) -> Iterator[tuple[Path, Path]]:
    """Every recording under the inputs with the folder it was found from: a plain folder itself; for a glob,
    the matched folder's parent (`fleet/robot-*` names robots); for a recording, its own folder."""
    for raw in inputs:
        matches = sorted(glob.glob(raw, recursive=True)) if glob.has_magic(raw) else [raw]
        if not matches:
            raise TriageError(f"no recordings match {raw!r}")
        for match in matches:
            path = Path(os.path.abspath(match))
            if not Path(match).exists():
                raise TriageError(f"no such folder or recording: {raw}")
            if is_recording(path):
                yield path, path.parent
            else:
                base = path.parent if glob.has_magic(raw) else path
                for rec in find_recordings(path, follow_links=True):  # a fleet folder of links to recordings
                    yield rec, base


def _robot_folder(folder: Path) -> Path:
    """The nearest folder at or above `folder` that is not a date: the robot of a robot folder given directly,
    or of a glob over robots and dates."""
    while is_date(folder.name) and folder.parent != folder:
        folder = folder.parent
    return folder


def expand(inputs: Iterable[str]) -> list[tuple[Path, str]]:
    """Recordings under folders or globs, nested at any depth, each with a label unique in this run: its path under
    the inputs' common folder, starting at or above its robot (see `robot_of`)."""
    found: list[tuple[Path, Path]] = []
    seen: set[Path] = set()
    for rec, base in _matches(inputs):
        real = rec.resolve()
        if real not in seen:
            seen.add(real)
            found.append((rec, base))
    if not found:
        return []
    root = Path(os.path.commonpath([str(base) for _, base in found]))
    above = _robot_folder(root).parent  # where a label starts that has no robot folder under the common one
    labels: set[str] = set()
    named: list[tuple[Path, str]] = []
    for rec, _ in found:
        rel = rec.relative_to(root).as_posix()
        if not robot_of(rel):
            rel = rec.relative_to(above).as_posix()
        if rel in labels:  # only a folder repeating its parent's name can get here; the full path is unique
            rel = rec.as_posix().lstrip("/")
        labels.add(rel)
        named.append((rec, rel))
    return named
