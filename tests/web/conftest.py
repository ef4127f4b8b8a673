from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.web.helpers import hostile_recording

PICKED = ["bagfile_5_1", "bagfile_8_1", "bagfile_12_1", "bagfile_19_1", "bagfile_20_1", "bagfile_10_1"]


@pytest.fixture(scope="session")
def webroot(suite: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder of runs for the page: six scenarios, a hostile recording and a corrupt one."""
    root = tmp_path_factory.mktemp("webroot")
    for name in PICKED:
        shutil.copytree(suite / name, root / name)
    hostile_recording(root / "hostile_run")
    corrupt = root / "corrupt_run"
    shutil.copytree(suite / "bagfile_5_2", corrupt)
    db = next(corrupt.glob("*.db3"))
    db.write_bytes(db.read_bytes()[:4096])
    return root
