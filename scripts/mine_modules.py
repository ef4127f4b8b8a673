"""Mine the MoveIt 2 and ros2_control message catalogues from mirrored sources (facts only, never their code).

    .venv/bin/python scripts/mine_modules.py --mirror DIR [--check]

DIR holds bare mirrors named `owner+name/repo` (e.g. moveit+moveit2/repo, ros-controls+ros2_control/repo,
ros-controls+ros2_controllers/repo). For every branch of `scripts/modules_mining.yaml` the script greps the C++
sources for RCLCPP_/RCUTILS_ log macros (ERROR/WARN/FATAL, also _STREAM/_THROTTLE/_ONCE/_EXPRESSION, and INFO
in the files named for goal and controller bookkeeping), `throw X("...")` texts, and the Python spawners'
`logger.error/warn/info(...)`; each format string becomes a regex (printf conversions, streamed and `+`-joined
expressions and f-string fields become `[\\s\\S]*?`; in `return_files`, the literals a function returns for its
caller to log), deduplicated across branches with `file:line@branch` for each. The curated rules of the config
then give an entry its cause, its kind (cause | symptom | noise | goal bookkeeping) and its meaning; the rest
stay in the catalogue as recognised lines with no cause, so an explainer can tell a known MoveIt line from an
unknown one. A line of a hardware interface also carries the hardware_interface callbacks that log it and the role
`hardware_roles` gives them (scripts/driver_functions.py); the log calls are read by scripts/log_calls.py.
Writes explainers/manipulation/moveit_catalogue.json and explainers/control/ros2_control_catalogue.json; `--check`
fails when the written files differ.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from driver_functions import CALLBACKS, callbacks_by_line, role_of
from log_calls import cpp_calls, fmt_calls, py_calls, returned

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "scripts" / "modules_mining.yaml"
WILD = r"[\s\S]*?"
LEVEL_NAMES = {"DEBUG": 10, "INFO": 20, "WARN": 30, "WARNING": 30, "ERROR": 40, "FATAL": 50, "THROW": 40}
START = r"(?:^|\]:? )"  # the message's start, or where a console format's last bracket ends
GOAL_KINDS = frozenset({"begin", "begin_server", "succeeded", "failed", "canceled", "end_server", "nominal"})


@dataclass
class Found:
    level: str
    file: str
    line: int
    branch: str
    pieces: list[str | None]  # literal text, or None for an expression the format does not fix
    callbacks: tuple[str, ...] = ()  # the hardware_interface callbacks it is logged in (driver_functions.py)


@dataclass
class Entry:
    pattern: str
    text: str
    level: str
    package: str
    open_end: bool = False
    sources: list[str] = field(default_factory=list)
    branches: list[str] = field(default_factory=list)
    callbacks: set[str] = field(default_factory=set)


def git(repo: Path, *args: str) -> str:
    return subprocess.run(["git", "-C", str(repo), *args], capture_output=True, text=True, check=True).stdout


def to_regex(pieces: list[str | None]) -> tuple[str, str, bool]:
    """(regex, the literal text with '…' for each expression, whether it ends in an expression) of a message's
    pieces. A message that begins with its literal is matched from the message's start only (a short format such
    as "Received request" must not match inside another module's line)."""
    parts: list[str] = []
    shown: list[str] = []
    for p in pieces:
        if p and "\n" in p and "".join(shown).strip():
            # a console prints each line of a message as a line of its own: match the first one
            head = p.split("\n", 1)[0]
            if head:
                parts.append(re.escape(head).replace("\\ ", " "))
                shown.append(head)
            break
        if p and "\n" in p:
            p = p.lstrip("\n").split("\n", 1)[0]
        if p is None or p == "":
            if p is None and (not parts or parts[-1] != WILD):
                parts.append(WILD)
                shown.append("…")
            continue
        run = "".join(shown).rsplit("…", 1)[-1]  # adjacent literals are one run of text
        cut = _first_sentence(p, len(run))
        parts.append(re.escape(cut).replace("\\ ", " "))
        shown.append(cut)
        if cut != p:
            break
    open_start = bool(parts) and parts[0] == WILD
    open_end = bool(parts) and parts[-1] == WILD
    while parts and parts[0] == WILD:
        parts.pop(0)
    while parts and parts[-1] == WILD:
        parts.pop()
    if not parts:
        return "", "", open_end
    if not open_end and parts[-1].endswith(("\\.", "!")) and len(parts[-1]) > 2:
        # a message's closing full stop comes and goes between releases (ros2_control 0.1.0's "Loader for
        # controller '…' not found" has none): a line is recognised with or without it
        parts[-1] += "?"
    return ("" if open_start else START) + "".join(parts), "".join(shown).strip("…").strip(), open_end


_SENTENCE_END = re.compile(r"[.!] (?=[A-Z])")


def _first_sentence(piece: str, before: int) -> str:
    """A long literal up to the end of its first sentence when that sentence alone is long (60 characters or
    more): releases add, drop or reword the advice that follows (the UR driver's calibration error), and such a
    sentence already tells the message apart."""
    m = _SENTENCE_END.search(piece)
    return piece[:m.start() + 1] if m is not None and before + m.start() >= 60 else piece


def _longest_literal(pieces: list[str | None]) -> int:
    return max((len(p.strip()) for p in pieces if p), default=0)


def mine_repo(repo: Path, branch: str, cfg: dict[str, Any]) -> Iterator[Found]:
    skip = re.compile(cfg["skip_paths"])
    info_files = re.compile(cfg.get("info_files", "^$"))
    return_files = re.compile(cfg.get("return_files", "^$"))
    files = [f for f in git(repo, "ls-tree", "-r", "--name-only", branch).splitlines()
             if f.endswith((".cpp", ".hpp", ".h", ".py")) and not skip.search(f)]
    texts = {f: git(repo, "show", f"{branch}:{f}") for f in files}
    placed = callbacks_by_line({f: t for f, t in texts.items() if not f.endswith(".py")})
    for f, text in texts.items():
        calls = py_calls(text) if f.endswith(".py") else (*cpp_calls(text), *fmt_calls(text))
        if return_files.search(f):
            calls = (*calls, *returned(text))
        for level, line, pieces in calls:
            if level in {"DEBUG"} or (level == "INFO" and not info_files.search(f) and not return_files.search(f)):
                continue
            if _longest_literal(pieces) < 6:
                continue  # "%s" alone, or a stream of variables: nothing to recognise a line by
            yield Found(level, f, line, branch, pieces, placed.get(f, {}).get(line, ()))


def package_of(path: str) -> str:
    parts = path.split("/")
    for k in range(len(parts) - 1, 0, -1):
        if parts[k] in {"src", "include", "controller_manager", "hardware_interface"} and k:
            return parts[k - 1] if parts[k] != parts[k - 1] else parts[k]
    return parts[0]


def collect(cfg: dict[str, Any], mirror: Path, module: str) -> list[Entry]:
    entries: dict[str, Entry] = {}
    for repo_cfg in cfg["modules"][module]["repos"]:
        repo = mirror / repo_cfg["mirror"] / "repo"
        for branch in repo_cfg["branches"]:
            for found in mine_repo(repo, branch, repo_cfg):
                pattern, text, open_end = to_regex(found.pieces)
                if not pattern:
                    continue
                e = entries.get(pattern)
                if e is None:
                    package = package_of(found.file)  # a library's top src/ or include/ folder: the repository's
                    package = repo_cfg["name"] if package in {"src", "include"} else package
                    e = entries[pattern] = Entry(pattern, text, found.level, package, open_end)
                elif LEVEL_NAMES[found.level] > LEVEL_NAMES[e.level] and found.level != "THROW":
                    e.level = found.level
                e.callbacks.update(found.callbacks)
                if branch not in e.branches:
                    e.branches.append(branch)
                    e.sources.append(f"{repo_cfg['name']}/{found.file}:{found.line}@{branch}")
    return list(entries.values())


def _sources(sources: list[str]) -> str:
    """`repo/path:L@branch (L2@branch2, ...)`: the path once when the branches agree on it."""
    first_path = sources[0].rsplit(":", 1)[0]
    rest = [s.rsplit(":", 1)[1] if s.rsplit(":", 1)[0] == first_path else s for s in sources[1:]]
    return sources[0] + (f" ({', '.join(rest)})" if rest else "")


def _slug(text: str) -> str:
    words = re.findall(r"[a-z0-9]+", text.lower())[:6]
    return "_".join(words) or "line"


def classify(entries: list[Entry], cfg: dict[str, Any], module: str) -> list[dict[str, Any]]:
    rules = [(re.compile(r["match"]), r) for r in cfg["modules"][module]["rules"]]
    used: set[str] = set()
    order = cfg["distro_of_branch"]
    out = []
    ids: set[str] = set()
    for e in sorted(entries, key=lambda x: (x.package, x.text)):
        rule = next((r for rx, r in rules if rx.search(e.text)), None)
        if rule is not None:
            used.add(rule["match"])
        base = f"{e.package}.{_slug(e.text)}"
        ident, k = base, 2
        while ident in ids:
            ident, k = f"{base}_{k}", k + 1
        ids.add(ident)
        distros = sorted({order[b] for b in e.branches}, key=list(order.values()).index)
        row: dict[str, Any] = {
            "id": ident, "role": e.package, "level": e.level, "package": e.package,
            "kind": rule["kind"] if rule else "other", "strength": rule.get("strength", "strong") if rule else "weak",
            "cause": rule.get("cause") if rule else None,
            "meaning": rule["meaning"] if rule else f"a {e.level.lower()} of {e.package} (no cause assigned)",
            # a goal's begin or end line is matched whole: its words recur inside other lines
            "distros": distros,
            "pattern": e.pattern + (r"\s*$" if rule and rule["kind"] in GOAL_KINDS and not e.open_end else ""),
            "text": e.text, "source": _sources(e.sources),
        }
        if e.callbacks:  # a driver's line: the callbacks it is logged in, and what that makes of an error there
            row["functions"] = [c for c in CALLBACKS if c in e.callbacks]
            row["hw_role"] = role_of(e.callbacks, e.text, cfg["modules"][module].get("hardware_roles"))
        out.append(row)
    unused = [m for m in (r["match"] for r in cfg["modules"][module]["rules"]) if m not in used]
    if unused:
        raise SystemExit(f"ERROR: {module}: rules that match no mined line: {unused}")
    return out


def dump(doc: dict[str, Any]) -> str:
    """JSON with one message per line: diffs of a re-mine read line by line."""
    head = {k: v for k, v in doc.items() if k != "messages"}
    body = ",\n".join("  " + json.dumps(m, ensure_ascii=False) for m in doc["messages"])
    return json.dumps(head, ensure_ascii=False)[:-1] + ', "messages": [\n' + body + "\n]}\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mirror", type=Path, required=True, help="folder of owner+name/repo bare mirrors")
    ap.add_argument("--check", action="store_true", help="fail when the committed catalogues differ")
    ap.add_argument("--module", action="append", help="only this module of the config (repeatable; default all): "
                    "a re-mine of one needs only its own mirrors")
    args = ap.parse_args(argv)
    cfg = yaml.safe_load(CONFIG.read_text(encoding="utf-8"))
    unknown = sorted(set(args.module or ()) - set(cfg["modules"]))
    if unknown:
        print(f"ERROR: no module {', '.join(unknown)} in {CONFIG.name}; use {', '.join(cfg['modules'])}",
              file=sys.stderr)
        return 2
    status = 0
    for module, mcfg in cfg["modules"].items():
        if args.module and module not in args.module:
            continue
        rows = classify(collect(cfg, args.mirror, module), cfg, module)
        doc = {"about": mcfg["about"], "distros": list(dict.fromkeys(cfg["distro_of_branch"].values())),
               "roles": mcfg["roles"], "error_codes": mcfg.get("error_codes", {}),
               "refinements": mcfg.get("refinements", []),
               **({"hardware_roles": mcfg["hardware_roles"]["roles"]} if "hardware_roles" in mcfg else {}),
               "messages": rows}
        target = ROOT / mcfg["out"]
        text = dump(doc)
        if args.check:
            if not target.is_file() or target.read_text(encoding="utf-8") != text:
                print(f"ERROR: {target.relative_to(ROOT)} is not what the miner writes", file=sys.stderr)
                status = 1
            continue
        target.write_text(text, encoding="utf-8")
        with_cause = sum(r["cause"] is not None for r in rows)
        print(f"{module}: {len(rows)} messages, {with_cause} with a cause -> {target.relative_to(ROOT)}")
    return status


if __name__ == "__main__":
    sys.exit(main())
