"""Do the answers hold when the same real lines are pasted another way? Every excerpt of the real-nav2 and
real-modules suites (their data files, as frozen) is run once as it is and once per way a person hands the same
console over, and each answer's verdict is compared with the plain one's.

Ways that keep every line (an answer should not change):
- docker: `docker compose logs` prints "nav2-1  | " in front of each line
- journal: `journalctl -u` of a robot started by systemd: "Nov 30 09:50:58 robot start.sh[918]: " in front, its
  local time (UTC+1 here) to the second, taken from the last stamp a node printed
- color: RCUTILS_COLORIZED_OUTPUT's escape sequences around WARN, ERROR and FATAL lines
- crlf: Windows line ends
Ways that drop lines (an answer may grow less sure, and must not claim more):
- noproc: a node run on its own (`ros2 run`), without launch's "[process-N] " in front
- errorsonly: only the WARN, ERROR and FATAL lines (and their indented continuations)
- tail20: only the last 20 lines (a console's end as people copy it, often its shutdown)

    .venv/bin/python scripts/probe_pastes.py [--ways docker journal ...] [--jobs 2] [--keep DIR]

Prints, per way: excerpts, verdicts that changed, how many became wrong, and the unsupported causes that appeared.
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import tempfile
import time
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "evals" / "data"
KEEP_ALL = ("docker", "journal", "color", "crlf")
DROP = ("noproc", "errorsonly", "tail20")
_STAMP = re.compile(r"\[(\d{10})\.\d+\]")
_LEVELS = ("[WARN]", "[ERROR]", "[FATAL]", "[WARNING]")
_COLOURS = {"[WARN]": "\x1b[33m", "[ERROR]": "\x1b[31m", "[FATAL]": "\x1b[31m"}
_PROC = re.compile(r"^\[[\w./$()-]+(?: [\w./$()-]+)*-\d+\] ")


def _journal(text: str) -> str:
    first = _STAMP.search(text)
    last = int(first[1]) if first else 1_700_000_000
    out = []
    for line in text.split("\n"):
        if m := _STAMP.search(line):
            last = int(m[1])
        out.append(time.strftime("%b %d %H:%M:%S", time.gmtime(last + 3600)) + " robot start.sh[918]: " + line)
    return "\n".join(out)


def _colour(line: str) -> str:
    for level, code in _COLOURS.items():
        if level in line:
            return line.replace(level, code + level, 1) + "\x1b[0m"
    return line


def _errors_only(text: str) -> str:
    keep, inside = [], False
    for line in text.split("\n"):
        if any(k in line for k in _LEVELS):
            inside = True
            keep.append(line)
        elif inside and line[:1].isspace():
            keep.append(line)
        else:
            inside = False
    return "\n".join(keep) + "\n" if keep else text


def pasted(way: str, text: str) -> str:
    """`text` (an excerpt's lines) as handed over `way`."""
    lines = text.split("\n")
    if way == "plain":
        return text
    if way == "docker":
        return "\n".join("nav2-1  | " + ln for ln in lines)
    if way == "journal":
        return _journal(text)
    if way == "color":
        return "\n".join(_colour(ln) for ln in lines)
    if way == "crlf":
        return "\r\n".join(lines)
    if way == "noproc":
        return "\n".join(_PROC.sub("", ln) for ln in lines)
    if way == "errorsonly":
        return _errors_only(text)
    if way == "tail20":
        return "\n".join([ln for ln in lines if ln.strip()][-20:]) + "\n"
    raise SystemExit(f"ERROR: unknown way {way!r}")


def _write(way: str, folder: Path) -> list[tuple[str, Path]]:
    out = []
    for family, suite in (("real_nav2", "real-nav2"), ("real_modules", "real-modules")):
        for data in sorted((DATA / family).glob("*.yaml")):
            entries = yaml.safe_load(data.read_text())
            for e in entries:
                e["lines"] = pasted(way, e["lines"])
            case = folder / way / f"{family}__{data.stem}.yaml"
            case.parent.mkdir(parents=True, exist_ok=True)
            case.write_text(yaml.safe_dump(entries, sort_keys=False, allow_unicode=True, width=10_000))
            out.append((suite, case))
    return out


def _run(suite: str, case: Path) -> dict[str, dict[str, object]]:
    out = case.with_suffix("")
    cmd = [sys.executable, "-m", "hexar", "eval", "--suite", suite, "--cases", str(case), "--llm", "none",
           "--out", str(out), "--no-figures"]
    done = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, check=False)
    if done.returncode != 0:
        raise SystemExit(f"ERROR: {' '.join(cmd)} failed: {done.stderr.strip()[-300:]}")
    report = json.loads((out / "report.json").read_text())
    return {f"{case.stem}:{e['id']}": e["text"] for e in report["excerpts"]}


def verdicts(way: str, folder: Path, jobs: int) -> dict[str, dict[str, object]]:
    with ThreadPoolExecutor(jobs) as pool:
        parts = pool.map(lambda sc: _run(*sc), _write(way, folder))
    return {k: v for part in parts for k, v in part.items()}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ways", nargs="+", default=[*KEEP_ALL, *DROP], choices=[*KEEP_ALL, *DROP])
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--keep", type=Path, help="keep the case files and reports here")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.keep or Path(tmp)
        plain = verdicts("plain", folder, args.jobs)
        print(f"{'way':<11} {'excerpts':>8} {'changed':>8} {'to wrong':>8}  new unsupported causes")
        for way in args.ways:
            now = verdicts(way, folder, args.jobs)
            changed = [k for k in plain if now[k]["verdict"] != plain[k]["verdict"]
                       or now[k]["unsupported"] != plain[k]["unsupported"]]
            wrong = [k for k in changed if now[k]["verdict"] == "wrong"]
            new: Counter[str] = Counter(c for k in changed for c in now[k]["unsupported"]  # type: ignore[attr-defined]
                                        if c not in plain[k]["unsupported"])  # type: ignore[operator]
            print(f"{way:<11} {len(plain):>8} {len(changed):>8} {len(wrong):>8}  "
                  + (", ".join(f"{c} {n}" for c, n in new.most_common()) or "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
