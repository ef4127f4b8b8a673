"""setup.sh installs one locked dependency set: the same versions for the demo, the tests and CI on any day."""

from __future__ import annotations

import os
import re
import subprocess
import tomllib
from importlib import metadata
from pathlib import Path

from packaging.markers import Marker
from packaging.requirements import Requirement
from packaging.utils import canonicalize_name
from packaging.version import Version

ROOT = Path(__file__).resolve().parents[2]
LOCK = ROOT / "requirements.lock"
SETUP = ROOT / "scripts" / "setup.sh"
# The extras setup.sh's lock must cover: what the README's two commands install, and `embedded`'s dependencies
# (llama-cpp-python itself is built from source by setup.sh --full).
LOCKED_EXTRAS = ("dev", "voice", "live", "ros", "mcp", "fleet", "embedded")
BUILT_FROM_SOURCE = {"llama-cpp-python"}


def _locked() -> list[tuple[str, Version, Marker | None, int]]:
    """(name, version, marker, number of hashes) for each entry of the lock."""
    entries = []
    text = LOCK.read_text("utf-8")
    for block in re.split(r"\n(?=[A-Za-z0-9])", text):
        head = block.split("\\", 1)[0].strip()
        if not head or head.startswith("#"):
            continue
        spec, _, marker = head.partition(";")
        name, _, version = spec.strip().partition("==")
        entries.append((canonicalize_name(name), Version(version), Marker(marker) if marker.strip() else None,
                        block.count("--hash=sha256:")))
    return entries


def _applies(marker: Marker | None) -> bool:
    return marker is None or marker.evaluate()


def test_every_locked_package_is_pinned_with_hashes() -> None:
    entries = _locked()
    assert len(entries) > 100
    assert all(hashes >= 1 for _, _, _, hashes in entries), [n for n, _, _, h in entries if not h]


def test_the_lock_covers_every_declared_dependency() -> None:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))["project"]
    declared = [Requirement(r) for r in project["dependencies"]]
    declared += [Requirement(r) for extra in LOCKED_EXTRAS for r in project["optional-dependencies"][extra]]
    locked = {(name, str(marker)): version for name, version, marker, _ in _locked()}
    by_name: dict[str, list[Version]] = {}
    for (name, _), version in locked.items():
        by_name.setdefault(name, []).append(version)
    missing = []
    for req in declared:
        name = canonicalize_name(req.name)
        if name in BUILT_FROM_SOURCE:
            continue
        versions = by_name.get(name, [])
        if not versions or not all(req.specifier.contains(v, prereleases=True) for v in versions):
            missing.append(f"{req} (locked: {[str(v) for v in versions]})")
    assert not missing, f"pyproject.toml declares what the lock lacks; run scripts/lock.sh: {missing}"


def test_the_environment_has_exactly_the_locked_versions() -> None:
    wrong = []
    for name, version, marker, _ in _locked():
        if not _applies(marker):
            continue
        try:
            installed = Version(metadata.version(name))
        except metadata.PackageNotFoundError:
            wrong.append(f"{name} not installed")
            continue
        if installed != version:
            wrong.append(f"{name} {installed}, locked {version}")
    assert not wrong, f"not the locked set (bash scripts/setup.sh installs it): {wrong[:10]}"


def test_setup_installs_from_the_lock_and_resolves_nothing_else() -> None:
    installs = [line.strip() for line in SETUP.read_text("utf-8").splitlines()
                if re.search(r"\$PIP install\b", line) and not line.strip().startswith("#")]
    assert any("--require-hashes" in line and "-r requirements.lock" in line for line in installs), installs
    # Everything else installs one named artefact without its dependencies (those came from the lock).
    others = [line for line in installs if "-r requirements.lock" not in line]
    assert others and all("--no-deps" in line for line in others), others
    assert all("--upgrade" not in line for line in installs), installs


def _fake_bin(tmp_path: Path, apt_body: str) -> dict[str, str]:
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "apt-get").write_text(f"#!/bin/sh\necho \"$*\" >> {tmp_path}/calls\n{apt_body}\n")
    (bin_dir / "sudo").write_text('#!/bin/sh\nexec "$@"\n')
    for tool in ("apt-get", "sudo"):
        (bin_dir / tool).chmod(0o755)
    return {**os.environ, "PATH": f"{bin_dir}:{os.environ['PATH']}", "HEXAR_APT_RETRY_DELAY": "0",
            "HEXAR_APT_TRIES": "3", "TMPDIR": str(tmp_path)}


def _apt_install(env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    script = f"source {ROOT / 'scripts' / 'apt_install.sh'}; apt_install sox espeak-ng"
    return subprocess.run(["bash", "-c", script], env=env, capture_output=True, text=True, timeout=60, check=False)


def test_a_busy_package_manager_is_retried_then_one_clear_line(tmp_path: Path) -> None:
    busy = ('echo "E: Could not get lock /var/lib/dpkg/lock-frontend. It is held by process 4242 (apt-get)" >&2\n'
            'echo "E: Unable to acquire the dpkg frontend lock (/var/lib/dpkg/lock-frontend), is another process '
            'using it?" >&2\nexit 100')
    done = _apt_install(_fake_bin(tmp_path, busy))
    assert done.returncode != 0
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("ERROR: could not install the Debian packages sox espeak-ng")
    assert "another process holds the package manager" in lines[0] and "3 tries" in lines[0]
    assert "Could not get lock" not in done.stdout + done.stderr
    assert (tmp_path / "calls").read_text().count("update") == 3


def test_a_package_manager_freed_between_tries_installs(tmp_path: Path) -> None:
    # busy on the first try only: the second try goes through and nothing is printed
    body = f'if [ ! -e {tmp_path}/once ]; then touch {tmp_path}/once; echo "E: Could not get lock" >&2; exit 100; fi'
    done = _apt_install(_fake_bin(tmp_path, body))
    assert done.returncode == 0 and done.stderr == "", done.stderr
    assert "install -y -qq sox espeak-ng" in (tmp_path / "calls").read_text()
