"""A seeded fuzz harness: hostile recordings and questions through the real CLI, checked against its promises.

Each example is drawn from `random.Random(seed)`, so a finding is reproduced by its seed alone. Kinds:
- `strings`: a simulated scenario whose every recorded text field may hold control characters, escape sequences
  (CSI, OSC 0/52), rich markup, bidi overrides, huge strings, and raw non-UTF-8 bytes;
- `task_info`: random JSON (NaN, Infinity, huge numbers, wrong types) published on /task_info;
- `damage`: random byte damage to the .db3 or .mcap file (overwrites, zeroed blocks, truncation, insertions),
  MCAP files carrying the CRCs a real rosbag2 recorder writes half of the time;
- `question`: hostile questions on the command line and in `--questions` files of any encoding.
A third of the examples also drive the web page's HTTP API and the MCP tools (tests/fuzz/surfaces.py).

Properties of every command run: no exception escapes `main`, exit code 0 or 2, no "internal error", no raw
control or invisible character in anything printed, strict JSON with `--json`, and every cause of an answer backed
by evidence whose topic and time match a message that exists in the recording.
"""

from __future__ import annotations

import contextlib
import io
import json
import random
import shutil
import struct
import unicodedata
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexar.cli import main
from hexar.evals.cases import scenario
from hexar.evals.scenarios.bag import TYPESTORE, BagBuilder
from hexar.evals.scenarios.suite import record
from hexar.events import contract as c
from hexar.events.errors import EventsError
from hexar.events.log import EventLog
from hexar.events.reader import read_recording
from hexar.explainers.base import Evidence
from hexar.explainers.evidence_check import exists
from hexar.explainers.tts import render as render_status
from hexar.safe_text import visible

_T = TYPESTORE.types
PIECES = [
    "\x1b[31m", "\x1b[2J\x1b[H", "\x1b]0;pwned\x07", "\x1b]52;c;ZWNobyBwd25lZA==\x07", "\x9b31m", "\x1bP1$r\x1b\\",
    "\x07", "\r", "\x00", "\x08\x08\x08", "\u202e", "\u2066", "\u200b", "\ufeff", "\U000e0041", "\u2028", "\x85",
    "[/]", "[bold red]", "[link=file:///etc/passwd]x[/link]", "[/bold]", "\\", "\\[", ":warning:", "%s%n", "{0}",
    "NaN", "-Infinity", "1e999", "\t", "\n", "[", "]", "}", "{", "'", '"', "null", "ERROR: ", "Traceback",
]
KINDS = ("strings", "task_info", "damage", "question")
QUESTIONS = ["What happened?", "Why didn't you bring it?", "Why did it take so long?", "why?", "and why was that?"]
BAD_UTF8 = [b"\xff", b"\xfe\xff", b"\xc3\x28", b"\xe2\x82", b"\xed\xa0\x80", b"\xf0\x9f\x98", b"\x80"]


def hostile_text(rng: random.Random) -> str:
    parts: list[str] = []
    for _ in range(rng.randint(0, 8)):
        roll = rng.random()
        if roll < 0.5:
            parts.append(rng.choice(PIECES))
        elif roll < 0.75:
            parts.append("".join(chr(rng.randint(0, 0x2FF)) for _ in range(rng.randint(1, 12))))
        elif roll < 0.9:
            parts.append("".join(chr(rng.choice([rng.randint(0, 0xD7FF), rng.randint(0xE000, 0x10FFFF)]))
                                 for _ in range(rng.randint(1, 6))))
        else:
            parts.append(rng.choice(["the path is blocked", "Goal failed", "kitchen", "say", "timeout_s"]))
    text = "".join(parts)
    if rng.random() < 0.03:
        text = text * (50_000 // max(1, len(text))) + rng.choice(PIECES)
    return text


def hostile_bytes(rng: random.Random) -> bytes:
    out = bytearray(hostile_text(rng).encode("utf-8", "surrogatepass"))
    for _ in range(rng.randint(1, 4)):
        pos = rng.randint(0, len(out))
        out[pos:pos] = rng.choice(BAD_UTF8)
    return bytes(out).replace(b"\x00", b"")


def _maybe(rng: random.Random, value: str, p: float) -> str:
    return hostile_text(rng) if rng.random() < p else value


def _cdr_string(data: bytes) -> bytes:
    """A std_msgs/msg/String in little-endian CDR with arbitrary (even non-UTF-8) bytes."""
    return b"\x00\x01\x00\x00" + struct.pack("<I", len(data) + 1) + data + b"\x00"


def _cdr_log(t: int, name: bytes, msg: bytes) -> bytes:
    """An rcl_interfaces/msg/Log in little-endian CDR whose name and msg are arbitrary bytes."""
    body = bytearray(struct.pack("<iIB", t // 10**9, t % 10**9, 40))

    def string(b: bytes) -> None:
        while len(body) % 4:
            body.append(0)
        body.extend(struct.pack("<I", len(b) + 1) + b + b"\x00")

    for part in (name, msg, b"", b""):
        string(part)
    while len(body) % 4:
        body.append(0)
    body.extend(struct.pack("<I", 0))
    return b"\x00\x01\x00\x00" + bytes(body)


def _mutate_task(rng: random.Random, data: str, p: float) -> str:
    obj = json.loads(data)
    obj["instruction"] = _maybe(rng, obj.get("instruction", ""), p)
    obj["task_error_msg"] = _maybe(rng, obj.get("task_error_msg", ""), p)
    if rng.random() < p / 4:
        obj["task_id"] = hostile_text(rng)
    for step in obj.get("skill_sequence", []):
        step["skill"] = _maybe(rng, step["skill"], p / 2)
        step["error_msg"] = _maybe(rng, step.get("error_msg", ""), p)
        if rng.random() < p:
            step["params"] = {hostile_text(rng): hostile_text(rng) for _ in range(rng.randint(1, 3))}
        if rng.random() < p / 4:
            step["status"] = hostile_text(rng)
    return json.dumps(obj)


def hostile_strings(rng: random.Random, b: BagBuilder) -> list[tuple[int, str, str, bytes]]:
    """Rewrite `b`'s recorded text in place; return extra raw messages carrying non-UTF-8 bytes."""
    p = rng.choice([0.05, 0.2, 0.6])
    for i, (t, topic, msgtype, m) in enumerate(b.messages):
        if msgtype == c.LOG_TYPE and rng.random() < p:
            m = _T[c.LOG_TYPE](stamp=m.stamp, level=m.level, name=_maybe(rng, m.name, 0.3),
                               msg=_maybe(rng, m.msg, 0.8) if rng.random() < 0.7 else m.msg + hostile_text(rng),
                               file=m.file, function=m.function, line=m.line)
        elif topic == c.TASK_INFO:
            m = _T[c.STRING_TYPE](data=_mutate_task(rng, m.data, p))
        elif msgtype == c.DIAG_TYPE and rng.random() < p:
            statuses = [_T["diagnostic_msgs/msg/DiagnosticStatus"](
                level=s.level, name=_maybe(rng, s.name, 0.1), message=_maybe(rng, s.message, 0.3),
                hardware_id=_maybe(rng, s.hardware_id, 0.5),
                values=[_T["diagnostic_msgs/msg/KeyValue"](key=_maybe(rng, kv.key, 0.1),
                                                           value=_maybe(rng, kv.value, 0.6)) for kv in s.values],
            ) for s in m.status]
            m = _T[c.DIAG_TYPE](header=m.header, status=statuses)
        b.messages[i] = (t, topic, msgtype, m)
    t0 = min(m[0] for m in b.messages)
    raw = []
    for k in range(rng.randint(0, 3)):
        raw.append((t0 + 1000 + k, c.ROSOUT, c.LOG_TYPE, _cdr_log(t0 + 1000 + k, hostile_bytes(rng),
                                                                 hostile_bytes(rng))))
    if rng.random() < 0.3:
        raw.append((t0 + 5000, c.TASK_INFO, c.STRING_TYPE, _cdr_string(hostile_bytes(rng))))
    return raw


def random_json(rng: random.Random, depth: int = 0) -> Any:
    roll = rng.random()
    if depth > 3 or roll < 0.4:
        return rng.choice([float("nan"), float("inf"), -float("inf"), 1e308, -(2**70), 0, True, None,
                           hostile_text(rng), "", 3.5, "Running", "failed", "succeeded"])
    if roll < 0.7:
        return [random_json(rng, depth + 1) for _ in range(rng.randint(0, 4))]
    keys = ["task_id", "instruction", "skill_sequence", "status", "params", "skill", "error_msg", "task_status"]
    return {rng.choice([*keys, hostile_text(rng)]): random_json(rng, depth + 1) for _ in range(rng.randint(0, 5))}


def random_task_info(rng: random.Random, b: BagBuilder) -> list[tuple[int, str, str, bytes]]:
    times = sorted(m[0] for m in b.messages)
    out = []
    for k in range(rng.randint(1, 6)):
        doc = random_json(rng)
        if rng.random() < 0.6:
            doc = {"task_id": random_json(rng, 3) if rng.random() < 0.3 else "fz" + str(k % 2),
                   "instruction": random_json(rng, 2), "task_status": random_json(rng, 3),
                   "skill_sequence": random_json(rng, 1) if rng.random() < 0.4 else
                   [{"skill": random_json(rng, 3), "params": random_json(rng, 2), "status": random_json(rng, 3),
                     "error_msg": random_json(rng, 3)} for _ in range(rng.randint(0, 3))]}
        text = json.dumps(doc, allow_nan=True)
        out.append((rng.choice(times) + k + 1, c.TASK_INFO, c.STRING_TYPE, _cdr_string(text.encode())))
    return out


def write(b: BagBuilder, raw: list[tuple[int, str, str, bytes]], out: Path, storage: str) -> Path:
    """`b`'s messages and the already-serialised `raw` ones as a rosbag2 recording."""
    from rosbags.rosbag2 import StoragePlugin, Writer

    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    msgs = [(t, topic, typ, TYPESTORE.serialize_cdr(m, typ)) for t, topic, typ, m in b.messages] + raw
    with Writer(out, version=9, storage_plugin=plugin) as writer:
        conns: dict[tuple[str, str], Any] = {}
        for t, topic, typ, data in sorted(msgs, key=lambda m: m[0]):
            if (topic, typ) not in conns:
                conns[(topic, typ)] = writer.add_connection(topic, typ, typestore=TYPESTORE)
            writer.write(conns[(topic, typ)], t, data)
    return out


def add_mcap_crcs(path: Path) -> None:
    """Fill in the chunk and summary CRCs that rosbags leaves at 0, as rosbag2's own MCAP writer does."""
    data = bytearray(path.read_bytes())
    pos = 8
    while pos + 9 <= len(data):
        opcode, length = struct.unpack_from("<BQ", data, pos)
        if opcode == 0x06:
            (clen,) = struct.unpack_from("<I", data, pos + 9 + 28)
            p = pos + 9 + 32 + clen
            (size,) = struct.unpack_from("<Q", data, p)
            struct.pack_into("<I", data, pos + 9 + 24, zlib.crc32(data[p + 8 : p + 8 + size]))
        if opcode == 0x02:
            (summary,) = struct.unpack_from("<Q", data, pos + 9)
            struct.pack_into("<I", data, pos + 9 + 16, zlib.crc32(data[summary : pos + 9 + 16]))
            break
        pos += 9 + length
    path.write_bytes(bytes(data))


def _find_all(data: bytearray, word: bytes) -> list[int]:
    found, pos = [], data.find(word)
    while pos >= 0:
        found.append(pos)
        pos = data.find(word, pos + 1)
    return found


def damage(rng: random.Random, path: Path) -> str:
    """Damage one storage file in place; return what was done."""
    data = bytearray(path.read_bytes())
    how = rng.choice(["flip", "flip", "payload", "payload", "zero", "truncate", "insert"])
    marks = [m for word in (b"Goal", b"kitchen", b"timeout", b"task_id", b"status", b"skill", b"/rosout")
             for m in _find_all(data, word)]
    if how == "payload" and marks:
        # inside a message's bytes, where sqlite keeps no checksum: the recording reads, with other data
        pos = rng.choice(marks)
        data[pos : pos + 4] = rng.randbytes(4)
    elif how in {"flip", "payload"}:
        for _ in range(rng.randint(1, 40)):
            data[rng.randrange(len(data))] = rng.randrange(256)
    elif how == "zero":
        start = rng.randrange(len(data))
        data[start : start + rng.randint(1, 4096)] = bytes(min(len(data) - start, 4096))[: rng.randint(1, 4096)]
    elif how == "truncate":
        del data[rng.randrange(len(data)) :]
    else:
        pos = rng.randrange(len(data))
        data[pos:pos] = rng.randbytes(rng.randint(1, 64))
    path.write_bytes(bytes(data))
    return how


def _bad_char(text: str) -> str | None:
    for ch in text:
        if ch != "\n" and unicodedata.category(ch) in {"Cc", "Cf", "Cs", "Zl", "Zp"}:
            return repr(ch)
    return None


def _strict(text: str) -> Any:
    def refuse(name: str) -> Any:
        raise ValueError(f"non-standard JSON constant {name}")

    return json.loads(text, parse_constant=refuse)


@dataclass
class Outcome:
    args: list[str]
    code: int
    out: str
    err: str
    problems: list[str] = field(default_factory=list)


def run_cli(args: list[str], stdin: str = "") -> Outcome:
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), _stdin(stdin):
            code = main(args)
    except BaseException as e:
        return Outcome(args, -1, out.getvalue(), err.getvalue(), [f"exception escaped: {type(e).__name__}: {e}"])
    result = Outcome(args, code, out.getvalue(), err.getvalue())
    if code not in (0, 2):
        result.problems.append(f"exit code {code}")
    if "Traceback (most recent call last)" in result.err or "internal error, please report" in result.err:
        result.problems.append("traceback or internal error: " + result.err[-300:])
    bad = _bad_char(result.out + result.err)
    if bad:
        result.problems.append(f"raw control character {bad} printed")
    if "--json" in args and code == 0:
        try:
            _strict(result.out) if not (args[0] == "ask" and "--questions" in args) else [
                _strict(line) for line in result.out.splitlines() if line.strip()]
        except ValueError as e:
            result.problems.append(f"invalid JSON: {e}")
    return result


@contextlib.contextmanager
def _stdin(text: str) -> Any:
    """Piped input, as `printf 'q\\n' | hexar chat RUN` gives it."""
    import sys

    saved = sys.stdin
    sys.stdin = io.StringIO(text)
    try:
        yield
    finally:
        sys.stdin = saved


def grounded(result: dict[str, Any], log: EventLog) -> list[str]:
    """Causes without evidence, and evidence that matches no message of the recording."""
    recorded = {(c.ROSOUT, r.t) for r in log.logs} | {(c.TASK_INFO, u.t) for u in log.task_updates}
    recorded |= {(c.AMCL_POSE, p.t) for p in log.poses}
    recorded |= {(s.topic, s.t) for flags in log.flags.values() for s in flags}
    recorded |= {(s.topic, s.t) for statuses in log.statuses.values() for s in statuses}
    problems = [f"cause {cause} without evidence" for cause in result.get("causes", [])
                if not any(ev["cause"] == cause for ev in result.get("evidence", []))]
    problems += [f"evidence on {ev['topic']} at {ev['t']} is in no recorded message"
                 for ev in result.get("evidence", []) if (ev["topic"], ev["t"]) not in recorded]
    problems += [f"evidence {visible(ev['item'][:80])!r} on {ev['topic']} is not what was recorded there"
                 for ev in result.get("evidence", []) if not _cited(log, Evidence(**ev))]
    return problems


def _cited(log: EventLog, ev: Evidence) -> bool:
    """evidence_check.exists, plus /task_info text as decoded (its raw JSON escapes non-ASCII text), plus the
    recorded text as it leaves HEXAR: JSON values carry control characters as visible escapes."""
    return _cited_raw(log, ev) or any(ev.item and (ev.item in v or v in ev.item)
                                      for v in (visible(x, keep_newlines=True) for x in _texts_at(log, ev)) if v)


def _texts_at(log: EventLog, ev: Evidence) -> list[str]:
    texts = [line.render() for line in log.logs if line.t == ev.t]
    texts += [render_status(r) for r in log.statuses.get(ev.topic, []) if r.t == ev.t]
    for u in log.task_updates:
        if u.t == ev.t:
            texts += [u.instruction, u.task_error_msg, u.task_id]
            for step in u.skills:
                texts += [step.skill, step.status, step.error_msg, str(step.params), step.label()]
                texts += [f"{k}={v}" for k, v in step.params.items()] + [str(v) for v in step.params.values()]
    return texts


def _cited_raw(log: EventLog, ev: Evidence) -> bool:
    if exists(log, ev):
        return True
    if ev.topic in log.statuses:
        # exists() parses "key = value" pairs, which hostile keys and values break; compare whole renderings
        return any(r.t == ev.t and ev.item == render_status(r) for r in log.statuses[ev.topic])
    if ev.topic != c.TASK_INFO:
        return False
    for u in log.task_updates:
        if u.t != ev.t:
            continue
        texts = [u.instruction, u.task_error_msg, u.task_id]
        for step in u.skills:
            texts += [step.skill, step.status, step.error_msg, str(step.params), step.label()]
            texts += [f"{k}={v}" for k, v in step.params.items()] + [str(v) for v in step.params.values()]
        if any(ev.item and (ev.item in text or (text and text in ev.item)) for text in texts):
            return True
    return False


def _ask_grounded(bag: Path, question: str, log: EventLog | None) -> Outcome:
    o = run_cli(["ask", str(bag), question, "--llm", "none", "--json"])
    if o.code == 0 and not o.problems:
        if log is None:
            o.problems.append("answered about a recording that cannot be read")
        else:
            o.problems += grounded(_strict(o.out), log)
    return o


def _read(bag: Path) -> EventLog | None:
    try:
        return read_recording(bag)
    except EventsError:
        return None


_BASES: dict[tuple[int, str], Path] = {}


def _base_bag(sid: int, storage: str, work: Path) -> Path:
    """One clean recording per scenario and storage, written once per process and copied per example."""
    key = (sid, storage)
    if key not in _BASES or not _BASES[key].exists():
        path = write(record(scenario(sid), 1), [], work / f"base_{sid}_{storage}", storage)
        _BASES[key] = path
    return _BASES[key]


def example(seed: int, work: Path) -> list[Outcome]:
    """Run one example; return every command's outcome (those with `problems` are findings)."""
    rng = random.Random(seed)
    kind = KINDS[seed % len(KINDS)]
    sid = rng.choice([1, 2, 3, 5, 6, 7, 8, 11, 13, 15, 19, 20])
    storage = rng.choice(["sqlite3", "mcap"])
    folder = work / f"ex{seed}"
    folder.mkdir(parents=True, exist_ok=True)
    bag = folder / "bag"
    outcomes: list[Outcome] = []
    try:
        if kind in {"strings", "task_info"}:
            b = record(scenario(sid), 1, seed=rng.randint(0, 3))
            raw = hostile_strings(rng, b) if kind == "strings" else random_task_info(rng, b)
            write(b, raw, bag, storage)
        elif kind == "damage":
            shutil.copytree(_base_bag(sid, storage, work), bag)
            target = next(p for p in bag.iterdir() if p.suffix in {".db3", ".mcap"})
            if storage == "mcap" and rng.random() < 0.5:
                add_mcap_crcs(target)
            damage(rng, target)
        else:
            shutil.copytree(_base_bag(sid, storage, work), bag)
        question = hostile_text(rng) if kind == "question" else rng.choice(QUESTIONS)
        if kind == "question" and rng.random() < 0.2:
            question += "\ud800"  # a lone surrogate, as a broken terminal may pass
        # One command per example keeps a long run affordable; over many seeds every command meets every kind.
        roll = rng.random()
        if roll < 0.5:
            outcomes.append(_ask_grounded(bag, question, _read(bag)))
        elif kind == "question":
            qfile = folder / "questions.txt"
            encode: Callable[[str], bytes] = rng.choice([
                lambda s: s.encode("utf-8", "surrogatepass"), lambda s: s.encode("utf-16", "surrogatepass"),
                lambda s: b"\xef\xbb\xbf" + s.encode("utf-8", "surrogatepass"), lambda s: hostile_bytes(rng)])
            qfile.write_bytes(encode("\n".join([question, *rng.sample(QUESTIONS, 2)])))
            outcomes.append(run_cli(["ask", str(bag), "--questions", str(qfile), "--llm", "none",
                                     *rng.choice([["--json"], ["-v"], []])]))
        else:
            others = [["ask", str(bag), question, "--llm", "none", "-v"], ["inspect", str(bag), "--json"],
                      ["inspect", str(bag)], ["runs", str(folder)], ["runs", str(folder), "--json"]]
            outcomes.append(run_cli(rng.choice(others)))
        # The other commands over the same recording; drawn after the choices above, so the seeds found by
        # earlier long runs still run what they ran then.
        if rng.random() < 0.4:
            more = [
                (["chat", str(bag), "--llm", "none", "--checkpoints", str(folder / "t.sqlite")],
                 f"{question}\nwhy?\n/task\n/evidence\nwhat else happened?\n"),
                (["triage", str(folder), "--out", str(work / f"triage{seed}"), "--workers", "1", "--no-figures"],
                 ""),
                (["annotate", str(bag), "--out", str(work / f"annotated{seed}.mcap")], ""),
                (["listen", str(bag), "--llm", "none", "--wav", str(folder / "missing.wav")], ""),
            ]
            args, piped = rng.choice(more)
            outcomes.append(run_cli(args, piped))
        # The web page's API and the MCP tools over the same recording and question; drawn last, so earlier
        # seeds still run what they ran before
        if rng.random() < 0.35:
            from tests.fuzz.surfaces import mcp, web

            outcomes.append(web(folder, bag, question, _read(bag)) if rng.random() < 0.5 else
                            mcp(folder, bag, question, rng))
    finally:
        for extra in (work / f"triage{seed}", work / f"annotated{seed}.mcap"):
            if extra.is_dir():
                shutil.rmtree(extra, ignore_errors=True)
            elif extra.exists():
                extra.unlink()
        shutil.rmtree(folder, ignore_errors=True)
    return outcomes


def findings(seed: int, work: Path) -> list[str]:
    return [f"seed {seed}: {' '.join(o.args[:1])} {o.args[2:] if len(o.args) > 2 else ''}: {p}"[:600]
            for o in example(seed, work) for p in o.problems]
