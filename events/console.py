"""Console output as log records: the formats ROS 2 prints and people paste when they quote it (launch.log too).

Formats read (a `NN: ` ctest prefix, a `name | ` docker-compose prefix and a `> ` quote prefix are removed):
- `[process-N] [LEVEL] [stamp] [logger]: msg`          ros2 launch, Foxy onwards
- `[LEVEL] [stamp] [logger]: msg`                       a node run on its own (`ros2 run`)
- `[process-N] [LEVEL] [logger]: msg`, `[LEVEL] [logger]: msg`   without stamps (Dashing/Eloquent-era output)
- `[process-N] [logger]: msg`, `logger: msg`            no level (hand-trimmed pastes)
- RCUTILS_CONSOLE_OUTPUT_FORMAT variants: `{date_time_with_ms}` ("2024-06-11 09:29:19.304") or
  `{time_as_nanoseconds}` as the stamp, a date-time in front of the line, level and stamp in one bracket, and the
  ROS 2 logging guide's ` ({function_name}() at {file_name}:{line_number})` after the message (kept as the record's
  function, file and line, as /rosout carries them)
- colour: RCUTILS_COLORIZED_OUTPUT's escape sequences, also where a paste lost the escape character ("[33m") or
  shows it in caret notation ("^[[33m")
- journald (`journalctl`, a robot started by robot_upstart or systemd): "Nov 14 22:13:20 host unit[pid]: " in front
- a Python traceback (an uncaught exception a Python node printed, rclpy's RCLError from rcl included) is one ERROR
  record: the exception's line first, then the traceback as printed ("Traceback (most recent call last):", the frames)
- Cyclone DDS's stderr lines behind a time prefix ("1795927356.580085 [0]     python: msg": domain, thread name), a
  WARN at least (the core prints only its fatal, error and warning categories there, ddsrt/src/log.c's log mask)
- anything else is a bare message; a line that starts lower-case or indented, a launch prefix with nothing after
  it, or a line after one that ended in whitespace, continues the message before it (console-wrapped text).
What the console did not print is synthesised and marked so: levels from the message's wording, increasing stamps
between (or around) the printed ones, and an empty logger name when none was printed (rcl's own value for lines
logged before a node exists, e.g. `[ERROR] [stamp] []: Caught exception ...`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from datetime import UTC, datetime

from hexar.events.records import TRACEBACK

LEVELS = {"DEBUG": 10, "INFO": 20, "WARN": 30, "WARNING": 30, "ERROR": 40, "FATAL": 50}
NS = 1_000_000_000
# A corpus line with no stamp at all gets stamps from here (2023-11-14), 100 ms apart.
BASE_NS = 1_700_000_000 * NS
STEP_NS = NS // 10

# a line's outer prefix: a numbered paste ("12: "), `grep -n` output ("115:[controller_server-2] …"), docker
# compose's "service | ", an editor's or `cat -n`'s line number column ("1124  [bt_navigator-16] …"), a quote
_OUTER = re.compile(r"^(?:\d+: |\d+:(?=\[)|\s*\d+(?:\t| {2,})(?=\[)|[\w.-]+\s+\| |> )")
# launch's process name is the command's basename, or the `name` a launch file gives it, spaces allowed
# ("[controller_manager fd_controller-4]"), or the command line as ros_gz_sim's launch gives it to launch
# ("[ruby $(which gz) sim-1]"): words joined by single spaces, then launch's "-N"
_PROC_NAME = r"[\w./$()-]+(?: [\w./$()-]+)*-\d+"
_PROC = rf"(?:\[(?P<proc>{_PROC_NAME})\]\s*)?"
_LEVEL = r"\[\s*(?P<level>DEBUG|INFO|WARN|WARNING|ERROR|FATAL)\]\s*"
# {time} (seconds), {time_as_nanoseconds} or {date_time_with_ms} ("2024-06-11 09:29:19.304", local time: read as UTC)
_DATE_TIME = r"\d{4}-\d{2}-\d{2}[ T]\d{2}:\d{2}:\d{2}(?:[.,]\d+)?"
_STAMP_TEXT = rf"\d+(?:\.\d+)?|{_DATE_TIME}"
_STAMP = rf"(?:\[(?P<stamp>{_STAMP_TEXT}|)\]\s*)?"
_LOGGER = rf"\[(?P<logger>[^\]\s]*|{_PROC_NAME})\]:\s?"
LEVELED = re.compile(rf"^{_PROC}{_LEVEL}{_STAMP}(?:{_LOGGER})?(?P<msg>.*)$")
# RCUTILS_CONSOLE_OUTPUT_FORMAT "[{severity} {time}] [{name}]: {message}": level and stamp in one bracket
LEVEL_STAMP = re.compile(rf"^{_PROC}\[\s*(?P<level>DEBUG|INFO|WARN|WARNING|ERROR|FATAL)\s+(?P<stamp>{_STAMP_TEXT})\]\s*"
                         rf"(?:{_LOGGER})?(?P<msg>.*)$")
NAMED = re.compile(rf"^{_PROC}{_LOGGER}(?P<msg>.*)$")
# RCUTILS_CONSOLE_OUTPUT_FORMAT "[{time}] [{name}]: {message}" or "[{time}] {message}": no level
STAMP_ONLY = re.compile(rf"^{_PROC}\[(?P<stamp>\d{{9,10}}\.\d+)\]\s+(?:{_LOGGER})?(?P<msg>\S.*)$")
# spdlog's default "[date] [info] msg", which drivers built on spdlog print beside ROS's own lines
SPDLOG = re.compile(rf"^{_PROC}\[(?P<level>trace|debug|info|warning|error|critical)\]\s+(?P<msg>\S.*)$")
_SPDLOG_LEVELS = {"trace": "DEBUG", "critical": "FATAL"}
# gz-common's console (gz/common/Console.cc: gzerr/gzwarn/gzmsg/gzdbg) as Gazebo prints it beside ROS's lines:
# "[Err] [Physics.cc:1801] msg", the source place when it prints one
GZ = re.compile(rf"^{_PROC}\[(?P<level>Err|Wrn|Msg|Dbg)\] (?:\[(?P<file>[\w.+-]+):(?P<line>\d+)\] )?(?P<msg>\S.*)$")
_GZ_LEVELS = {"Err": "ERROR", "Wrn": "WARN", "Msg": "INFO", "Dbg": "DEBUG"}
PLAIN_NAMED = re.compile(r"^(?P<logger>[A-Za-z_][\w.]*):\s+(?P<msg>\S.*)$")
PROC_ONLY = re.compile(rf"^\[(?P<proc>{_PROC_NAME})\](?P<rest>.*)$")
# Wall-clock consoles: "10:33:12  msg" (a summary pasted with times) and RCUTILS_CONSOLE_OUTPUT_FORMAT variants
# such as "[ WARN][6:31:18.730 PM -03][controller_server]: msg". Their times become stamps on BASE_NS's day.
_CLOCK = r"(?P<clock>\d{1,2}:\d{2}:\d{2}(?:\.\d+)?)(?:\s*(?P<ampm>AM|PM))?(?:\s*[+-]\d{2}(?::?\d{2})?)?"
CLOCK_LEVELED = re.compile(rf"^{_PROC}{_LEVEL}\[{_CLOCK}\]\s*(?:{_LOGGER})?(?P<msg>.*)$")
CLOCK_PREFIX = re.compile(rf"^{_CLOCK}\s+(?P<rest>\S.*)$")
# launch's screen format with timestamps ("{created:.7f} {line}"): the wall time it printed the line, in epoch seconds
EPOCH_PREFIX = re.compile(r"^(?P<at>\d{9,10}\.\d+)\s+(?P<rest>\[.*)$")
# a date-time in front of the line ("[{date_time_with_ms}] [{severity}] ...", or bare)
DATE_PREFIX = re.compile(rf"^\[?(?P<at>{_DATE_TIME})\]?\s+(?P<rest>\S.*)$")
# journald's short formats (`journalctl` of a robot started by systemd or robot_upstart): "Nov 14 22:13:20 host
# unit[pid]: ", "2024-06-11T09:29:19+0000 host unit[pid]: "; the time stamps the records that print none
JOURNAL_PREFIX = re.compile(r"^(?:[A-Z][a-z]{2} [ \d]\d |\d{4}-\d{2}-\d{2}T)(?P<clock>\d{2}:\d{2}:\d{2}(?:\.\d+)?)\S* "
                            r"\S+ [^\s:\[]+(?:\[\d+\])?: (?P<rest>.*)$")
# RCUTILS_COLORIZED_OUTPUT's colours: escape sequences, shown "^[[33m" by `cat -v`, or "[33m" where a paste lost the
# escape character (at the start of the record, behind launch's prefix, and the closing reset)
_ESCAPE = re.compile(r"(?:\x1b|\^\[)\[[0-9;]*m")
_LOST_ESCAPE = re.compile(rf"^(?P<head>(?:\[{_PROC_NAME}\]\s*)?)(?:\[\d{{1,2}}(?:;\d{{1,2}})*m)+|(?:\[\d{{1,2}}m)+\s*$")
# the Cyclone DDS core's own log line behind its "{sec}.{usec} " time: "[{domain id}] {thread name, 16 wide}: msg"
CYCLONE = re.compile(r"^\[(?:\d+|-)\]\s+[^:\[\]]{1,16}:\s+(?P<msg>\S.*)$")
# CPython's traceback.print_exception: the header (TRACEBACK), "  File ..." frames with their source lines, then the
# exception's own line, unindented ("ValueError: ...", "rclpy._rclpy_pybind11.RCLError: ...", or a bare class name)
# CPython's warnings.formatwarning: "{file}:{line}: {category}: {message}" (then the source line, indented)
PY_WARNING = re.compile(r"^(?P<file>\S+\.py):(?P<line>\d+): (?P<category>\w*Warning): (?P<msg>.*)$")
_EXCEPTION_LINE = re.compile(r"^[A-Za-z_][\w.]*(?::\s.*)?$")
# the ROS 2 logging guide's format "... {message} ({function_name}() at {file_name}:{line_number})"
_WHERE = re.compile(r"\s\((?P<function>\S*?)\(\) at (?P<file>\S+):(?P<line>\d+)\)\s*$")
# Wording that decides a synthesised level; Nav2's own lines of these kinds are WARN/ERROR.
# glibc's malloc_printerr texts ("malloc(): memory corruption", "double free or corruption (out)", "free(): invalid
# pointer", "corrupted size vs. prev_size") are the process's last words: glibc aborts right after printing them.
ERROR_WORDS = re.compile(r"\b(error|exception|failed|fail|fatal|abort(ed|ing)?|died|illegal instruction|"
                         r"segmentation fault|core dumped|SIG(ILL|SEGV|ABRT)|memory corruption|double free|"
                         r"corrupted (size|double-linked list|top size)|invalid (pointer|chunk size|next size))\b",
                         re.I)
WARN_WORDS = re.compile(r"\b(warn\w*|timed out|time out|dropping|cannot|could not|couldn't|unable|exceeded|"
                        r"not available|does not exist|out of (map )?bounds|(highly |strongly )?recommended)\b", re.I)


@dataclass
class ConsoleLine:
    """One log record as read from a console excerpt; `synthesised` names the fields the console did not print."""

    stamp_ns: int | None
    level: int
    name: str
    msg: str
    process: str = ""
    synthesised: set[str] = field(default_factory=set)
    file: str = ""
    function: str = ""
    line: int = 0


def _fraction_ns(digits: str) -> int:
    """The nanoseconds of a second's decimal digits ("304" -> 304_000_000)."""
    return int((digits + "000000000")[:9])


def _stamp_ns(text: str) -> int:
    if "." not in text and "-" not in text and len(text) >= 16:  # {time_as_nanoseconds}
        return int(text)
    whole, _, frac = text.replace(",", ".").partition(".")
    if "-" in whole:  # {date_time_with_ms}
        day = datetime.strptime(whole.replace("T", " "), "%Y-%m-%d %H:%M:%S").replace(tzinfo=UTC)
        return int(day.timestamp()) * NS + _fraction_ns(frac)
    return int(whole) * NS + _fraction_ns(frac)


def infer_level(msg: str) -> int:
    if ERROR_WORDS.search(msg):
        return LEVELS["ERROR"]
    if WARN_WORDS.search(msg):
        return LEVELS["WARN"]
    return LEVELS["INFO"]


def _clock_ns(clock: str, ampm: str | None) -> int:
    h, m, sec = clock.split(":")
    hours = int(h) % 12 + (12 if ampm == "PM" else 0) if ampm else int(h)
    whole, _, frac = sec.partition(".")
    day = BASE_NS - BASE_NS % (86_400 * NS)
    return day + (hours * 3600 + int(m) * 60 + int(whole)) * NS + _fraction_ns(frac)


def _record(level: str | None, stamp: str | None, logger: str | None, msg: str, proc: str | None,
            stamp_ns: int | None = None) -> ConsoleLine:
    made: set[str] = set()
    if level is None:
        made.add("level")
    if not stamp and stamp_ns is None:
        made.add("stamp")
    if logger is None:
        made.add("name")
    return ConsoleLine(
        stamp_ns=_stamp_ns(stamp) if stamp else stamp_ns,
        level=LEVELS[level] if level is not None else infer_level(msg),
        name=logger or "",
        msg=msg,
        process=proc or "",
        synthesised=made,
    )


def _is_continuation(raw: str, previous_raw: str, records: Sequence[ConsoleLine]) -> bool:
    if not records:
        return False
    if raw[:1].isspace() or raw[:1].islower():
        return True
    return previous_raw[-1:].isspace()


def _stamp_all(records: Sequence[ConsoleLine], stamp_ns: int, keep_own: bool) -> None:
    """`records` stamped with a prefix's time (unless `keep_own` and a record printed its own stamp)."""
    for r in records:
        if not (keep_own and r.stamp_ns is not None):
            r.stamp_ns = stamp_ns
            r.synthesised.discard("stamp")


def _behind_prefix(rest: str, stamp_ns: int, records: list[ConsoleLine], keep_own: bool) -> None:
    """The records of a line printed behind a time prefix, stamped with that time (unless `keep_own` and the line
    prints its own stamp)."""
    inner: list[ConsoleLine] = []
    _parse_line(rest, "", inner)
    _stamp_all(inner, stamp_ns, keep_own)
    records.extend(inner)


def _parse_line(line: str, previous: str, records: list[ConsoleLine]) -> None:
    if _in_traceback(line, records):
        return
    w = PY_WARNING.match(line)
    if w:
        records.append(_record("WARN", None, None, f"{w['category']}: {w['msg']}", None))
        records[-1].file, records[-1].line = w["file"], int(w["line"])
        return
    c = CLOCK_LEVELED.match(line)
    if c:
        records.append(_record(c["level"].upper(), None, c["logger"], c["msg"], c["proc"],
                               _clock_ns(c["clock"], c["ampm"])))
        return
    t = CLOCK_PREFIX.match(line)
    if t:
        _behind_prefix(t["rest"], _clock_ns(t["clock"], t["ampm"]), records, keep_own=False)
        return
    e = EPOCH_PREFIX.match(line) or DATE_PREFIX.match(line)
    if e and _in_traceback(e["rest"], records):  # launch.log stamps every line of a traceback on its own
        return
    if e and (y := CYCLONE.match(e["rest"])):
        records.append(_record("WARN", e["at"], None, y["msg"], None))
        return
    if e:  # the node's own stamp, where printed, is the record's
        _behind_prefix(e["rest"], _stamp_ns(e["at"]), records, keep_own=True)
        return
    m = LEVELED.match(line) or LEVEL_STAMP.match(line)
    if m:
        msg = m["msg"] if m["logger"] is not None else re.sub(r"^:\s*", "", m["msg"])  # "[ERROR] : msg"
        records.append(_record(m["level"].upper(), m["stamp"], m["logger"], msg, m["proc"]))
        return
    o = STAMP_ONLY.match(line)
    if o:
        records.append(_record(None, o["stamp"], o["logger"], o["msg"], o["proc"]))
        return
    d = SPDLOG.match(line)
    if d:
        level = d["level"].upper()
        records.append(_record(_SPDLOG_LEVELS.get(d["level"], level), None, None, d["msg"], d["proc"]))
        return
    z = GZ.match(line)
    if z:
        records.append(_record(_GZ_LEVELS[z["level"]], None, None, z["msg"], z["proc"]))
        records[-1].file, records[-1].line = z["file"] or "", int(z["line"] or 0)
        return
    n = NAMED.match(line)
    if n:
        records.append(_record(None, None, n["logger"], n["msg"], n["proc"]))
        return
    p = PROC_ONLY.match(line)
    proc, rest = (p["proc"], p["rest"]) if p else (None, line)
    if p and (not rest.strip() or rest[1:2].isspace()):
        if records and rest.strip():  # launch prints each line of a multi-line message behind its prefix
            records[-1].msg += "\n" + rest.strip()
        elif rest.strip():  # the excerpt begins inside such a message (an exception's what()): kept, not dropped
            records.append(_record(None, None, None, rest.strip(), proc))
        return
    q = PLAIN_NAMED.match(rest.strip())
    if q:
        records.append(_record(None, None, q["logger"], q["msg"], proc))
    elif _is_continuation(rest if p else line, previous, records) and (not p or records[-1].process == proc):
        # (behind launch's prefix, a line continues only its own process's message, never another's)
        records[-1].msg += "\n" + rest.strip()
    else:
        records.append(_record(None, None, None, rest.strip(), proc))


_RCL_AT = re.compile(r", at \S+:\d+$")  # rcutils' error state: the message, then where it was set


def _in_traceback(line: str, records: list[ConsoleLine]) -> bool:
    """Whether `line` went into the traceback its process's last record holds (see _traceback_line): behind launch's
    prefix, other processes' lines may come between; without one, only the last record can be it."""
    p = PROC_ONLY.match(line)
    proc = p["proc"] if p else ""
    for r in reversed(records[-50:]):
        if r.process != proc and proc:
            continue
        if r.process == proc and (r.msg.startswith(TRACEBACK) or "exception" in r.synthesised):
            return _traceback_line(line, r)
        return False
    return False


def _traceback_line(line: str, tb: ConsoleLine) -> bool:
    """Whether `line` belongs to the open traceback `tb` (its frames, then the exception's line, which closes it:
    moved in front, so the record begins with what went wrong). Behind launch's prefix, only its own process's."""
    p = PROC_ONLY.match(line)
    proc, rest = (p["proc"], p["rest"][1:] if p["rest"][:1] == " " else p["rest"]) if p else ("", line)
    if proc != tb.process or not rest.strip():
        return False
    if "exception" in tb.synthesised:  # the exception's message goes on ("\n, at /project/src/rcl/node.c:249")
        said, _, frames = tb.msg.partition(f"\n{TRACEBACK}")
        # rcl words an error "<message>, at <file>:<line>": until that place is printed, the message goes on
        # (rmw_fastrtps' "…security libraries\nPlease compile Fast DDS …, at …/participant.cpp:406, at …")
        unfinished = _RCL_AT.search(said) is None and _RCL_AT.search(rest) is not None
        if not rest[:1].isspace() and not rest.startswith(",") and not unfinished:
            return False
        tb.msg = f"{said}\n{rest.rstrip()}\n{TRACEBACK}{frames}"
        return True
    if rest[:1].isspace():
        tb.msg += "\n" + rest.strip()
        return True
    if _EXCEPTION_LINE.match(rest.strip()) is None or rest.startswith(TRACEBACK):
        return False
    tb.msg = f"{rest.strip()}\n{tb.msg}"
    tb.level = LEVELS["ERROR"]
    tb.synthesised = (tb.synthesised - {"level"}) | {"exception"}
    return True


def _outer(line: str) -> str:
    """`line` without its outer prefixes, stacked as tools stack them (`docker compose logs | grep -n`: "nav2-1  |
    115:[controller_server-2] ...")."""
    for _ in range(3):
        inner = _OUTER.sub("", line, count=1)
        if inner == line:
            break
        line = inner
    return line


def _on_nodes_clock(records: list[ConsoleLine], journal: dict[int, int], printed: dict[int, int]) -> None:
    """Records stamped by journald's prefix alone (`journal`: index -> the prefix's time) moved onto the clock of the
    stamps the nodes printed (`printed`: the records behind a prefix that print their own). journald prints local
    wall time, to the second, on no stated day; a node prints seconds since the epoch. So the prefix's time is shifted
    by the median difference of the lines that show both, and kept after the record printed before it (a microsecond
    later at least: lines of one second stay in the order printed, which is the order logged) and not after the
    next stamp a node printed."""
    if not journal:
        return
    both = sorted((records[i].stamp_ns or 0) - at for i, at in printed.items())
    shift = both[len(both) // 2] if both else 0
    after: list[int | None] = [None] * len(records)  # the next stamp a node printed after each record
    for k in range(len(records) - 2, -1, -1):
        nxt = records[k + 1]
        after[k] = nxt.stamp_ns if k + 1 not in journal and nxt.stamp_ns is not None else after[k + 1]
    for i, at in sorted(journal.items()):
        t = at + shift
        before = records[i - 1].stamp_ns if i > 0 else None
        t = t if before is None else max(t, before + 1000)
        records[i].stamp_ns = t if after[i] is None else min(t, after[i] or t)


def parse_console(text: str) -> list[ConsoleLine]:
    """The log records of a pasted console excerpt, in the order printed (stamps may be missing: see `stamped`)."""
    records: list[ConsoleLine] = []
    previous = ""
    journal: dict[int, int] = {}  # records stamped by journald's prefix alone: index -> the prefix's time
    printed: dict[int, int] = {}  # records behind a journald prefix that print their own stamp: index -> the prefix's
    for raw in text.splitlines():
        line = _ESCAPE.sub("", raw)
        j = JOURNAL_PREFIX.match(line)
        at = _clock_ns(j["clock"], None) if j else None
        if j:
            line = j["rest"]
        line = _LOST_ESCAPE.sub(lambda m: m["head"] or "", _outer(line))
        if line.strip():
            n = len(records)
            _parse_line(line, previous, records)
            if at is not None:  # not through _behind_prefix: a journal's wrapped line still continues the one before
                for i in range(n, len(records)):
                    (printed if records[i].stamp_ns is not None else journal)[i] = at
                _stamp_all(records[n:], at, keep_own=True)
        previous = line
    _on_nodes_clock(records, journal, printed)
    for r in records:
        r.msg = r.msg.rstrip()
        if w := _WHERE.search(r.msg):
            r.msg, r.function, r.file, r.line = r.msg[: w.start()].rstrip(), w["function"], w["file"], int(w["line"])
        if "level" in r.synthesised:
            r.level = infer_level(r.msg)
    return records


def stamped(records: Sequence[ConsoleLine]) -> list[ConsoleLine]:
    """`records` with every stamp set: printed stamps kept, missing ones spread between their printed neighbours
    (or 100 ms apart before the first / after the last printed one, or from BASE_NS when none is printed)."""
    known = [i for i, r in enumerate(records) if r.stamp_ns is not None]
    out = [replace(r, synthesised=set(r.synthesised)) for r in records]
    if not known:
        for i, r in enumerate(out):
            r.stamp_ns = BASE_NS + i * STEP_NS
        return out
    for i, r in enumerate(out):
        if r.stamp_ns is not None:
            continue
        before = max((k for k in known if k < i), default=None)
        after = min((k for k in known if k > i), default=None)
        if before is not None and after is not None:
            lo, hi = records[before].stamp_ns, records[after].stamp_ns
            assert lo is not None and hi is not None
            span = max(hi - lo, 0)
            r.stamp_ns = lo + span * (i - before) // (after - before) if span else lo + (i - before)
        elif before is not None:
            lo = records[before].stamp_ns
            assert lo is not None
            r.stamp_ns = lo + (i - before) * STEP_NS
        else:
            assert after is not None
            hi = records[after].stamp_ns
            assert hi is not None
            r.stamp_ns = hi - (after - i) * STEP_NS
    return out
