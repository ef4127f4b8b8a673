"""The page's state: the folder of runs, decoded recordings (a few, most recent), findings and chat sessions,
and with `--live` one more run: the robot's LiveLog (web/live.py)."""

from __future__ import annotations

import hashlib
import json
import threading
import time
from collections import OrderedDict
from pathlib import Path
from typing import Any

from hexar.confined import confine, leaving
from hexar.events.errors import NoTaskError
from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.web.errors import WebError
from hexar.web.live import LIVE, LiveSource, Snapshot
from hexar.web.pagedata import Findings, cause_words, filtered_lines, recordings, run_detail, task_summary
from hexar.workspace import recording_name


def shown(path: Path) -> str:
    """A path as the page may show it: relative to where the server was started, `~/...` under the home folder,
    else only its last two parts; never this machine's absolute layout (a page can be read by other sites'
    scripts if anything goes wrong, and screenshots travel)."""
    if not path.is_absolute():
        return path.as_posix()
    for base, prefix in ((Path.cwd(), ""), (Path.home(), "~/")):
        if path.is_relative_to(base) and path != base:
            return prefix + path.relative_to(base).as_posix()
    return "/".join(path.parts[-2:])


WALK_FRESH_S = 10.0
KEEP_LOGS = 6  # an hour-long recording decodes to a few hundred MB; keep only the runs being looked at


class Store:
    def __init__(self, root: Path | None, llm: str = "auto", checkpoints: Path | None = None,
                 live: LiveSource | None = None) -> None:
        from hexar.agent.session import default_checkpoints

        self.root = root
        self.live = live
        self.llm = llm
        self.checkpoints = checkpoints or default_checkpoints()
        self.findings = Findings()
        if live is not None:
            live.shared = self.findings
        self._logs: OrderedDict[str, EventLog] = OrderedDict()
        self._lock = threading.Lock()
        self._rows: dict[str, tuple[float, dict[str, Any]]] = {}
        self._sessions: dict[str, Any] = {}
        self._session_lock = threading.Lock()
        self._ask_lock = threading.Lock()
        self._backend: Any = None
        self._worker: threading.Thread | None = None
        self._walked: tuple[float, dict[str, Path]] = (float("-inf"), {})
        names = {self.name_of(p) for p in self._recordings()}  # a missing folder is the one-line error, before serving
        if live is not None and LIVE in names:
            raise WebError(f"{root} holds a recording named {LIVE!r}, the live run's name: rename it to use --live")

    def _recordings(self) -> list[Path]:
        """The folder's recordings, walked afresh (each walk also refreshes what `path` looks names up in)."""
        found = [] if self.root is None else recordings(self.root)
        with self._lock:
            self._walked = (time.monotonic(), {self.name_of(p): p for p in found})
        return found

    def name_of(self, path: Path) -> str:
        """A recording's name on the page and in its API: its path under the folder (`robot1/run_3`)."""
        return path.name if self.root is None else recording_name(self.root, path)

    def clean(self, message: str) -> str:
        """An error message with the served folder's absolute location replaced by its shown name."""
        if self.root is None:
            return message
        for where in sorted({str(self.root.resolve()), str(self.root.absolute())}, key=len, reverse=True):
            message = message.replace(where, shown(self.root))
        return message

    def path(self, name: str) -> Path:
        """A recording of the folder by name; nothing outside the folder can be named. One page view asks for
        the same run many times (timeline, path, evidence, chat): within WALK_FRESH_S of the last walk of the folder
        a name is looked up in it, and a name it does not hold walks the folder again (a run just recorded)."""
        with self._lock:
            walked, by_name = self._walked
        if time.monotonic() - walked > WALK_FRESH_S or name not in by_name or not by_name[name].exists():
            self._recordings()
            with self._lock:
                by_name = self._walked[1]
        if self.root is not None and name in by_name:
            return confine(self.root, by_name[name], name)
        where = f"in {self.root}" if self.root is not None else "here: only the live robot is shown"
        raise WebError(f"no recording named {name!r} {where}")

    def log(self, name: str) -> EventLog:
        from hexar.events import read_recording

        if self.live is not None and name == LIVE:
            return self.live.snapshot().log
        with self._lock:
            if name in self._logs:
                self._logs.move_to_end(name)
                return self._logs[name]
        log = read_recording(self.path(name))
        with self._lock:
            self._logs[name] = log
            while len(self._logs) > KEEP_LOGS:
                self._logs.popitem(last=False)
        return log

    def task(self, name: str, ref: str | None) -> tuple[EventLog, Task]:
        log = self.log(name)
        return log, log.task(ref or None)

    # runs list ---------------------------------------------------------------------------------------------
    def _row(self, path: Path) -> dict[str, Any]:
        from hexar.events import EventsError, read_tasks

        stamp = path.stat().st_mtime
        name = self.name_of(path)
        cached = self._rows.get(name)
        if cached and cached[0] == stamp:
            return cached[1]
        out = leaving(self.root, path) if self.root is not None else None
        if out is not None:
            row = {"recording": name, "tasks": 0, "latest": None, "modules": [],
                   "error": f"ERROR: {out.name!r} is a link to a file outside the served folder: not read"}
            self._rows[name] = (stamp, row)
            return row
        try:
            log = read_tasks(path)  # tasks derived from Nav2 goals too, as `hexar runs` lists them
            task = log.task() if log.tasks else None
            row = {"recording": name, "tasks": len(log.tasks), "error": "",
                   "latest": task_summary(task) if task else None,
                   "modules": self.findings.modules(task) if task else []}
        except EventsError as e:
            row = {"recording": name, "tasks": 0, "error": self.clean(str(e)), "latest": None, "modules": []}
        self._rows[name] = (stamp, row)
        return row

    def runs(self) -> dict[str, Any]:
        rows = []
        pending = 0
        for path in self._recordings():
            row = dict(self._row(path))
            found = self.findings.cached((row["recording"], row["latest"]["task_id"])) if row["latest"] else []
            row["causes"] = None if found is None else sorted({c for f in found for c in f["causes"]})
            pending += found is None
            rows.append(row)
        if pending:
            self._start_worker()
        if self.live is not None:
            rows.insert(0, self._live_row(self.live))
        words = {cid: cause_words(cid) for r in rows for cid in r["causes"] or []}  # the list shows words, not ids
        return {"root": "" if self.root is None else shown(self.root), "runs": rows, "pending": pending,
                "cause_words": words}

    def _live_row(self, live: LiveSource) -> dict[str, Any]:
        snap = live.snapshot()
        task = snap.log.task() if snap.log.tasks else None
        return {"recording": LIVE, "live": True, "tasks": len(snap.log.tasks), "error": "",
                "latest": task_summary(task) if task else None,
                "modules": self.findings.modules(task) if task else [],
                "causes": sorted({c for f in snap.explain(task) for c in f["causes"]}) if task else []}

    def _start_worker(self) -> None:
        """Find each run's causes in the background so the list can be filtered by cause."""
        if self._worker is not None and self._worker.is_alive():
            return

        def work() -> None:
            from hexar.events import EventsError, read_recording

            for path in self._recordings():
                row = self._row(path)
                if not row["latest"] or self.findings.cached((row["recording"], row["latest"]["task_id"])) is not None:
                    continue
                try:
                    log = read_recording(path)
                    self.findings.get(row["recording"], log, log.task(row["latest"]["task_id"]))
                except (EventsError, WebError):
                    continue

        self._worker = threading.Thread(target=work, name="hexar-web-causes", daemon=True)
        self._worker.start()

    # one run -----------------------------------------------------------------------------------------------
    def explained(self, name: str, ref: str | None) -> tuple[EventLog, Task, list[dict[str, Any]]]:
        """The task and its findings, both from one snapshot when the run is live."""
        if self.live is not None and name == LIVE:
            snap = self.live.snapshot()
            task = snap.log.task(ref or None)
            return snap.log, task, snap.explain(task)
        log, task = self.task(name, ref)
        return log, task, self.findings.get(name, log, task)

    def run(self, name: str, ref: str | None, since: str | None = None) -> dict[str, Any]:
        if self.live is not None and name == LIVE:
            return self.live_run(self.live, ref, since)
        detail = run_detail(name, *self.explained(name, ref))
        detail["chat"] = {"recording_path": shown(self.path(name)), "checkpoints": shown(self.checkpoints)}
        return detail

    def live_run(self, live: LiveSource, ref: str | None, since: str | None) -> dict[str, Any]:
        """The live run like a recording's, with a version: a page that already shows version `since` gets only
        that nothing changed. A robot with no task yet is the CLI's one line, not an error."""
        snap = live.snapshot()
        view = snap.views.get(ref or "")
        if view is None:  # built once per snapshot and task, however many pages poll
            view = snap.views[ref or ""] = self._live_view(snap, ref)
        if since is not None and since == view["version"]:
            return {"recording": LIVE, "live": True, "version": view["version"], "unchanged": True}
        return view

    def _live_view(self, snap: Snapshot, ref: str | None) -> dict[str, Any]:
        head = {"recording": LIVE, "live": True, "storage": "live", "warnings": list(snap.log.warnings)}
        try:
            task = snap.log.task(ref or None)
        except NoTaskError as err:
            view = {**head, "no_task": str(err), "tasks": []}
        else:
            view = run_detail(LIVE, snap.log, task, snap.explain(task))
            view.update(head)
            view["chat"] = {"recording_path": None, "checkpoints": shown(self.checkpoints)}
        # the version is what the page shows: a robot that only publishes poses and log lines after the task
        # ended changes the snapshot, not the task's view, and the page is then not redrawn
        drawn = {k: v for k, v in view.items() if k not in {"start_ns", "duration_s"}}
        digest = hashlib.sha1(json.dumps(drawn, sort_keys=True).encode(), usedforsecurity=False)
        view["version"] = digest.hexdigest()[:16]
        return view

    def lines(self, name: str, ref: str | None) -> dict[str, Any]:
        log, task = self.task(name, ref)
        return filtered_lines(log, task)

    def plot(self, name: str, ref: str | None) -> bytes:
        from hexar.web.plot import build

        log, task, found = self.explained(name, ref)
        result = {"answer": " ".join(f["text"] for f in found), "causes": [c for f in found for c in f["causes"]],
                  "evidence": [e for f in found for e in f["evidence"]]}
        return build(log, task, result).png(dpi=80)

    # chat --------------------------------------------------------------------------------------------------
    def backend(self) -> Any:
        from hexar.agent.backends import resolve

        with self._session_lock:
            if self._backend is None:
                self._backend = resolve(self.llm)
            return self._backend

    def session(self, name: str) -> Any:
        from hexar.agent.context import RunSettings
        from hexar.agent.session import Session

        live = self.live.snapshot().log if self.live is not None and name == LIVE else None
        path = Path(LIVE) if live is not None else self.path(name)
        backend = self.backend()
        with self._session_lock:
            if name not in self._sessions:
                # one lock for every session: they share the backend, and an in-process model is not reentrant
                self._sessions[name] = (Session(RunSettings(recording=path, llm=self.llm), backend=backend,
                                                checkpoints=self.checkpoints, log=live), self._ask_lock)
            return self._sessions[name]

    def ask(self, name: str, question: str, thread: str | None, task: str | None) -> dict[str, Any]:
        session, lock = self.session(name)
        with lock:
            live = self.live if name == LIVE else None
            if live is not None:
                session.use_log(live.snapshot(fresh=True).log)  # as the live node does: the newest data
            try:
                result: dict[str, Any] = session.ask(question, thread=thread or None, task=task or None)
            except NoTaskError as err:
                if live is None or session.context.log.tasks:  # a task asked for that is gone: the error says so
                    raise
                from hexar.live.present import no_task_answer

                # as `hexar serve` answers it: the person hears why there is nothing to explain yet
                result = no_task_answer(session.context.log.logs, err, thread)
            if live is not None:
                from hexar.live.present import shape

                # worded as `hexar serve` words it: the robot is still at it, and there is no recording
                shape(result, session.context.log.tasks, live.log.contact, live.log.newest)
        if "recording" in result and name != LIVE:
            result["recording"] = shown(Path(result["recording"]))
        for ev in result["evidence"]:
            ev["key"] = f"{ev['topic']}|{ev['t']}"  # the page's row id: JavaScript numbers cannot hold a ns stamp
        return result

    def history(self, name: str, thread: str) -> list[dict[str, Any]]:
        session, lock = self.session(name)
        with lock:
            return list(session.history(thread))

    def close(self) -> None:
        if self.live is not None:
            self.live.close()
