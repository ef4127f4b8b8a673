"""A served folder's recordings stay inside it: a symlink (the folder itself, its metadata.yaml, a .db3 or
.mcap in it) that points outside the folder is refused, so a link cannot make the web page or `hexar mcp`
read a file elsewhere on the machine."""

from __future__ import annotations

from pathlib import Path

from hexar.errors import LinkOutsideError


def leaving(root: Path, path: Path) -> Path | None:
    """The first of `path` and (for a folder) its entries whose real location is outside `root`, or None."""
    real_root = root.resolve()
    checked = [path]
    if path.is_dir():
        checked += sorted(path.iterdir())
    for p in checked:
        try:
            real = p.resolve()
        except (OSError, RuntimeError):  # a symlink loop
            return p
        if real != real_root and not real.is_relative_to(real_root):
            return p
    return None


def confine(root: Path, path: Path, shown: str) -> Path:
    """`path`, or LinkOutsideError naming it as `shown` when it or a file of it links out of `root`."""
    out = leaving(root, path)
    if out is not None:
        what = shown if out == path else f"{shown}/{out.name}"
        raise LinkOutsideError(f"{what!r} is a link to a file outside the served folder: refused")
    return path
