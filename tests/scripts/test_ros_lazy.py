"""scripts/hexar_ros_lazy.pth: the ROS 2 wheels' start-up re-execution stays out of the `hexar` command's start,
and every other Python program in the environment still gets the wheels' library path."""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

from hexar.cli import release_ros_start_mark

ROOT = Path(__file__).resolve().parents[2]
WHEELS = importlib.util.find_spec("ros_wheels_bootstrapper") is not None
needs_wheels = pytest.mark.skipif(not WHEELS, reason="only the ROS 2 Kilted wheels re-execute Python at start-up")
PROBE = ("import json, os, sys\n"
         "print(json.dumps({'mark': os.environ.get('_HEXAR_ROS_LAZY'),"
         " 'ros_libs': 'ros_' in os.environ.get('LD_LIBRARY_PATH', '')}))\n")


def _shell_env() -> dict[str, str]:
    """The environment of a shell that never ran the wheels' bootstrap."""
    drop = {"LD_LIBRARY_PATH", "_ROS_WHEELS_BOOTSTRAP_COMPLETE", "_HEXAR_ROS_LAZY", "_HEXAR_ROS_REEXEC"}
    return {k: v for k, v in os.environ.items() if k not in drop}


def _probe(script: Path) -> dict[str, object]:
    script.write_text(PROBE, "utf-8")
    done = subprocess.run([sys.executable, str(script)], env=_shell_env(), capture_output=True, text=True,
                          timeout=60, check=True)
    return dict(json.loads(done.stdout))


@needs_wheels
def test_setup_installs_the_mark_beside_the_wheels_bootstrap() -> None:
    site = Path(sysconfig.get_paths()["purelib"])
    installed = site / "hexar_ros_lazy.pth"
    assert installed.is_file(), "scripts/setup.sh installs hexar_ros_lazy.pth where the ROS wheels are"
    assert installed.read_text("utf-8") == (ROOT / "scripts" / "hexar_ros_lazy.pth").read_text("utf-8")
    # .pth files run in name order: the mark must be set before the wheels' bootstrap looks for it
    assert sorted([installed.name, "ros_wheels_bootstrapper.pth"])[0] == installed.name


@needs_wheels
def test_the_hexar_command_starts_once_and_other_programs_still_get_the_ros_libraries(tmp_path: Path) -> None:
    hexar = _probe(tmp_path / "hexar")
    assert hexar == {"mark": "1", "ros_libs": False}  # not re-executed: the library path was never set
    robot = _probe(tmp_path / "robot.py")
    assert robot == {"mark": None, "ros_libs": True}  # the wheels' bootstrap ran as it always does


def test_the_cli_drops_the_mark_so_programs_it_starts_bootstrap_as_usual(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("_HEXAR_ROS_LAZY", "1")
    monkeypatch.setenv("_ROS_WHEELS_BOOTSTRAP_COMPLETE", "1")
    release_ros_start_mark()
    assert "_HEXAR_ROS_LAZY" not in os.environ and "_ROS_WHEELS_BOOTSTRAP_COMPLETE" not in os.environ


def test_a_bootstrap_the_user_asked_for_is_left_alone(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("_HEXAR_ROS_LAZY", raising=False)
    monkeypatch.setenv("_ROS_WHEELS_BOOTSTRAP_COMPLETE", "1")
    release_ros_start_mark()
    assert os.environ["_ROS_WHEELS_BOOTSTRAP_COMPLETE"] == "1"
