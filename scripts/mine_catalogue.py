"""Mine a log-message catalogue from git mirrors of ROS 2 repositories (generic: the config says what to read).

    python scripts/mine_catalogue.py --mirrors DIR [--config explainers/stack/sources.yaml]
                                     [--out explainers/stack/stack_catalogue.json]

DIR holds one bare or working git directory per repository, as `DIR/<owner>+<name>/repo` (what the `fetch` tool of
this project's sessions writes) or `DIR/<owner>+<name>` or `DIR/<name>`. For each repository of the config, on each
distro branch that exists, every C/C++/Python source file under the listed packages (tests excluded) is read with
`git grep`/`git cat-file`, never checked out; every WARN/ERROR/FATAL logging call, thrown or raised exception text
and rcl error message becomes an entry:

    {"pattern", "text", "level", "form", "layer", "package", "source": "file:line@branch", "distros", "role", "cause"}

Entries equal in (pattern, level, layer) across branches are merged, their distros joined; `source` is the newest
branch's. `role` and `cause` come from the config's rules (first match wins), else from the level. A repository or
branch that is missing is reported on stderr and skipped; the output says which were read (`mined`).
Only facts are written (message texts and where they are), never the repositories' code.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import yaml

from hexar.explainers.stack.catalogue import literal_key
from hexar.explainers.stack.mining import Call, cpp_calls, literal_length, literals, py_calls, to_display, to_pattern

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / "explainers" / "stack" / "sources.yaml"
OUT = ROOT / "explainers" / "stack" / "stack_catalogue.json"
DISTRO_ORDER = ("foxy", "galactic", "humble", "iron", "jazzy", "kilted", "rolling")
SOURCE_EXT = (".c", ".cc", ".cpp", ".cxx", ".h", ".hh", ".hpp", ".py")
START = r"RCLCPP_(WARN|ERROR|FATAL)|(Exception|Error)\.__init__\(|RCUTILS_LOG_(WARN|ERROR|FATAL)|SET_ERROR_MSG|" \
        r"throw |raise |gzerr|ignerr|gzwarn|" \
        r"ignwarn|logger[A-Za-z_]*(\(\))?\.(warn|warning|error|fatal|critical|exception)\(|logging\.(warn|error)"
_TESTS = re.compile(r"(^|/)(test|tests|testing|system_tests|nav2_system_tests|benchmark|examples?|doc|docs)/|"
                    r"(^|/)test_[^/]*$|_test\.(c|cc|cpp|py)$")


class MineError(Exception):
    """The config is unusable or no repository could be read."""


def git(repo: Path, *args: str, data: bytes | None = None) -> bytes:
    done = subprocess.run(["git", "-C", str(repo), *args], input=data, capture_output=True, check=False)
    if done.returncode not in (0, 1):  # 1: git grep found nothing
        raise MineError(f"git {' '.join(args[:2])} in {repo.name}: {done.stderr.decode(errors='replace').strip()}")
    return done.stdout


def find_mirror(root: Path, name: str) -> Path | None:
    owner, repo = name.split("/")
    for cand in (root / f"{owner}+{repo}" / "repo", root / f"{owner}+{repo}", root / repo):
        if cand.is_dir():
            return cand
    return None


def branches(repo: Path) -> set[str]:
    out = git(repo, "for-each-ref", "--format=%(refname:short)", "refs/heads", "refs/remotes")
    return {b.split("/", 1)[1] if b.startswith("origin/") else b for b in out.decode().split()}


def files_with_calls(repo: Path, branch: str, packages: Iterable[str], wrappers: Iterable[str],
                     exclude: Iterable[str] = ()) -> list[str]:
    specs = [f"{p}/*{ext}" for p in packages for ext in SOURCE_EXT] or [f"*{ext}" for ext in SOURCE_EXT]
    specs += [f":(exclude){x}" for x in exclude]  # e.g. a vendored file the mirror stores without its content
    out = git(repo, "grep", "-l", "-E", "|".join([START, *(rf"\b{w}\s*\(" for w in wrappers)]), branch, "--", *specs)
    paths = [ln.split(":", 1)[1] for ln in out.decode(errors="replace").splitlines() if ":" in ln]
    return sorted(p for p in set(paths) if not _TESTS.search(p))


def literal_files(repo: Path, branch: str, extras: list[dict[str, Any]]) -> list[str]:
    """The files a repository's `literals` globs name at `branch`."""
    if not extras:
        return []
    out = git(repo, "ls-tree", "-r", "--name-only", branch)
    names = out.decode(errors="replace").splitlines()
    return [n for n in names if any(Path(n).match(x["glob"]) for x in extras) and not _TESTS.search(n)]


def read_blobs(repo: Path, branch: str, paths: list[str]) -> dict[str, str]:
    """The files' text at `branch`, through one `git cat-file --batch`."""
    if not paths:
        return {}
    raw = git(repo, "cat-file", "--batch", data="".join(f"{branch}:{p}\n" for p in paths).encode())
    out: dict[str, str] = {}
    pos = 0
    for path in paths:
        header_end = raw.index(b"\n", pos)
        header = raw[pos:header_end].split()
        if len(header) < 3 or header[1] != b"blob":
            pos = header_end + 1
            continue
        size = int(header[2])
        out[path] = raw[header_end + 1:header_end + 1 + size].decode("utf-8", errors="replace")
        pos = header_end + 1 + size + 1
    return out


def classify(text: str, level: str, layer: str, package: str, rules: list[dict[str, Any]]) -> tuple[str, str | None]:
    for rule in rules:
        if rule.get("layer") not in (None, layer) or rule.get("package") not in (None, package) \
                or rule.get("level") not in (None, level):
            continue
        if re.search(rule.get("text", ""), text):
            return str(rule["role"]), rule.get("cause")
    return ("cause" if level in ("ERROR", "FATAL") else "symptom"), None


def package_of(path: str, packages: dict[str, str] | list[str]) -> tuple[str, str | None]:
    """(package folder, the layer it overrides to)."""
    top = path.split("/", 1)[0]
    if isinstance(packages, dict) and top in packages:
        return top, packages[top]
    return (top if "/" in path else ""), None


def mine_repo(repo: Path, spec: dict[str, Any], min_literal: int, rules: list[dict[str, Any]],
              merged: dict[tuple[str, str, str], dict[str, Any]], log: list[str]) -> None:
    have = branches(repo)
    packages = spec.get("packages") or []
    for branch, distros in spec["branches"].items():
        if branch not in have:
            log.append(f"{spec['name']}: no branch {branch}")
            continue
        paths = files_with_calls(repo, branch, list(packages), spec.get("wrappers") or {}, spec.get("exclude") or ())
        # a file of messages built away from any call (validate_topic_name.c's reasons) is read for its literals
        paths = sorted({*paths, *literal_files(repo, branch, spec.get("literals") or [])})
        texts = read_blobs(repo, branch, paths)
        for path, src in texts.items():
            package, layer = package_of(path, packages)
            wrappers = spec.get("wrappers") or {}
            calls: list[Call] = list(py_calls(src) if path.endswith(".py") else cpp_calls(src, wrappers))
            for extra in spec.get("literals") or []:
                if Path(path).match(extra["glob"]) or path == extra["glob"]:
                    calls += [Call(n, extra["level"], "reason", t) for n, t in literals(src, extra["regex"])]
            for call in calls:
                if literal_length(call.text) < min_literal:
                    continue
                _add(merged, call, layer or spec["layer"], package, f"{path}:{call.line}@{branch}", distros, rules)
        log.append(f"{spec['name']}@{branch}: {len(texts)} files")


def _add(merged: dict[tuple[str, str, str], dict[str, Any]], call: Call, layer: str, package: str, source: str,
         distros: list[str], rules: list[dict[str, Any]]) -> None:
    pattern = to_pattern(call.text)
    key = (pattern, call.level, layer)
    entry = merged.get(key)
    if entry is None:
        text = to_display(call.text)
        role, cause = classify(text, call.level, layer, package, rules)
        merged[key] = {"pattern": pattern, "text": text, "level": call.level, "form": call.form, "layer": layer,
                       "package": package, "source": source, "distros": list(distros), "role": role,
                       "cause": cause, "key": literal_key(pattern)}
        return
    newer = [d for d in distros if d not in entry["distros"]]
    entry["distros"] = sorted(set(entry["distros"]) | set(distros), key=DISTRO_ORDER.index)
    if newer and DISTRO_ORDER.index(newer[-1]) >= DISTRO_ORDER.index(entry["distros"][-1]):
        entry["source"] = source


def mine(config: dict[str, Any], mirrors: Path) -> dict[str, Any]:
    merged: dict[tuple[str, str, str], dict[str, Any]] = {}
    log: list[str] = []
    read: list[str] = []
    for spec in config["repos"]:
        repo = find_mirror(mirrors, spec["name"])
        if repo is None:
            log.append(f"{spec['name']}: no mirror under {mirrors.name}")
            continue
        mine_repo(repo, spec, int(config.get("min_literal", 10)), config.get("rules") or [], merged, log)
        read.append(spec["name"])
    if not read:
        raise MineError("no repository of the config was found under the mirrors folder")
    for line in log:
        print(line, file=sys.stderr)
    entries = sorted(merged.values(), key=lambda e: (e["layer"], e["package"], e["source"]))
    return {"about": "mined by scripts/mine_catalogue.py from the config explainers/stack/sources.yaml; "
                     "fields: see explainers/stack/catalogue.py",
            "distros": list(DISTRO_ORDER), "mined": read, "entries": entries}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--mirrors", type=Path, required=True, help="folder of git mirrors")
    ap.add_argument("--config", type=Path, default=CONFIG)
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args(argv)
    try:
        config = yaml.safe_load(args.config.read_text(encoding="utf-8"))
        if not isinstance(config, dict) or not isinstance(config.get("repos"), list):
            raise MineError(f"{args.config.name}: a mapping with a `repos` list is needed")
        data = mine(config, args.mirrors)
    except (OSError, yaml.YAMLError, MineError, KeyError, ValueError) as err:
        print(f"ERROR: {err}", file=sys.stderr)
        return 1
    args.out.write_text(json.dumps(data, indent=0, ensure_ascii=False) + "\n", encoding="utf-8")
    roles: dict[str, int] = {}
    for e in data["entries"]:
        roles[e["role"]] = roles.get(e["role"], 0) + 1
    print(f"{len(data['entries'])} entries from {len(data['mined'])} repositories: {roles}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
