"""`hexar triage`: every task of every recording, explained without an LLM, on a process pool or on Ray.

Resumable: each finished recording is appended as one JSON line to OUT/results.jsonl at once, so a crash or
Ctrl-C keeps what is done and a re-run skips it. The tables, report and figures are rebuilt from that file.
"""

from __future__ import annotations

import contextlib
import importlib.util
import json
import os
import re
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

from hexar.fleet.errors import TriageError
from hexar.fleet.inputs import expand, robot_of
from hexar.fleet.local import default_workers, one_math_thread, run_local

RESULTS = "results.jsonl"


@dataclass(frozen=True)
class TriageOptions:
    inputs: tuple[str, ...]
    out: Path
    workers: int | None = None
    ray: str | None = None  # None: local pool; "": a local Ray instance; else a cluster address
    figures: bool = True
    progress: bool = True


def load_results(out: Path) -> dict[str, dict[str, Any]]:
    """The finished recordings by key; a line cut short by a crash is dropped (its recording runs again)."""
    path = out / RESULTS
    if not path.is_file():
        return {}
    done: dict[str, dict[str, Any]] = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        try:
            item = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(item, dict) and "key" in item:
            done[item["key"]] = item
    return done


def triage_command(opts: TriageOptions, console: Console) -> int:
    if opts.workers is not None and opts.workers < 1:
        raise TriageError(f"--workers must be 1 or more, not {opts.workers}")
    workers = opts.workers or default_workers()
    one_math_thread()
    found = [(str(path.resolve()), rel) for path, rel in expand(opts.inputs)]
    if not found:
        raise TriageError(f"no recordings under {', '.join(opts.inputs)}")
    try:
        opts.out.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise TriageError(f"cannot write to {opts.out}: {err}") from err
    parquet = parquet_available()
    if not parquet:
        console.print("[yellow]pyarrow is not installed: writing tasks.jsonl only, no tasks.parquet "
                      "(pip install 'hexar\\[fleet]')[/yellow]")
    earlier = load_results(opts.out)
    todo = [(path, rel) for path, rel in found if path not in earlier]
    where = (f"Ray ({opts.ray or 'a local instance'})" if opts.ray is not None
             else f"{workers} worker{'s' if workers > 1 else ''}")
    console.print(f"{len(found)} recordings: {len(found) - len(todo)} done before, {len(todo)} to triage on {where}")
    interrupted = False
    results_file = opts.out / RESULTS
    if results_file.is_file() and results_file.stat().st_size:
        with results_file.open("rb+") as f:
            f.seek(-1, os.SEEK_END)
            if f.read(1) != b"\n":
                f.write(b"\n")  # a crash cut the last line short: start a fresh one, or the next result is lost too
    new: list[str] = []
    with results_file.open("a", encoding="utf-8") as sink, _progress(console, opts.progress) as bar:
        job = bar.add_task("triage", total=len(todo))
        drawn = [0.0]

        def on_done(lines: list[str]) -> None:
            sink.write("".join(line + "\n" for line in lines))
            sink.flush()
            new.extend(lines)
            bar.advance(job, len(lines))
            # drawn at most ten times a second: a redraw costs about as much as a small recording's triage
            if (now := time.monotonic()) - drawn[0] >= 0.1 or len(new) == len(todo):
                drawn[0] = now
                bar.refresh()

        try:
            if opts.ray is not None and todo:  # nothing left to do: no cluster to start or reach
                from hexar.fleet.on_ray import run_ray

                run_ray(todo, opts.ray, opts.workers, on_done)
            else:
                run_local(todo, workers, on_done, meanwhile=_import_report)
        except KeyboardInterrupt:
            interrupted = True
    from hexar.fleet.report import count, write_outputs

    # What the results file now holds, without reading it again; in the inputs' order, whoever finished first.
    finished = {**earlier, **{item["key"]: item for item in map(json.loads, new)}}
    results = [relabel(finished[path], rel) for path, rel in found if path in finished]
    summary = write_outputs(results, opts.out, figures=opts.figures, parquet=parquet)
    bad = [r for r in results if r["error"]]
    # as report.md counts them: a "finding" is a success worth a look, never a failure's cause
    console.print(f"{count(summary['recordings'], 'recording')}, {count(summary['tasks'], 'task')}: "
                  f"{summary['failed']} failed or wrongly planned, {summary['findings']} succeeded with a finding "
                  f"worth a look; {len(bad)} unreadable")
    for r in bad[:20]:
        console.print(f"  [yellow]unreadable[/yellow] {escape(r['recording'])}: {escape(r['error'])}")
    for r in [r for r in results if r.get("recovered")][:20]:
        how = r["recovered"][0].removeprefix("recovered: ")
        console.print(f"  [cyan]recovered[/cyan] {escape(r['recording'])}: {escape(how)}")
    if len(bad) > 20:
        console.print(f"  ... and {len(bad) - 20} more in {opts.out / 'report.md'}")
    console.print(f"wrote {opts.out / 'tasks.parquet'}, tasks.jsonl, report.md" if parquet else
                  f"wrote {opts.out / 'tasks.jsonl'}, report.md (no tasks.parquet: pyarrow is not installed)")
    if interrupted:
        console.print(f"[yellow]interrupted: {len(results)} of {len(found)} recordings done; run again to "
                      "finish the rest[/yellow]")
        return 130
    return 0


def relabel(result: dict[str, Any], rel: str) -> dict[str, Any]:
    """A recording finished by an earlier run named by this run's inputs: labels stay unique within one report."""
    result["recording"] = rel
    for row in result["rows"]:
        row["recording"], row["robot"] = rel, robot_of(rel)
    return result


def _import_report() -> None:
    """The report's modules and pyarrow's Parquet writer, imported while the workers triage rather than after."""
    with contextlib.suppress(ImportError):  # said in one line where the report needs it
        import hexar.fleet.report  # noqa: F401
    with contextlib.suppress(ImportError):  # no pyarrow: the same (a missing one does not stop the import above)
        import pyarrow.json
        import pyarrow.parquet  # noqa: F401


def parquet_available() -> bool:
    """Parquet needs pyarrow (the `fleet` extra): asked before the work, so a plain install still gets its tables.
    Found, not imported: the import is the report's, after the work (a missing one is then a one-line error)."""
    try:
        return importlib.util.find_spec("pyarrow") is not None
    except (ImportError, ValueError):  # a module entry set to None, or a broken package
        return False


# A Ray address as `--ray ADDRESS` gives it: the flag takes no value, so the address arrives among the inputs.
_RAY_ADDRESS = re.compile(r"auto|local|ray://\S+|[\w.-]+:\d+")


def ray_target(inputs: list[str], ray: bool, address: str | None) -> tuple[list[str], str | None]:
    """The inputs, and where Ray runs: None for the local pool, "" for a local Ray instance, else an address."""
    if address is None and ray:
        given = [x for x in inputs if _RAY_ADDRESS.fullmatch(x) and not Path(x).exists()]
        if len(given) > 1:
            raise TriageError(f"two Ray addresses: {', '.join(given)}")
        address = given[0] if given else "local"
        inputs = [x for x in inputs if x not in given]
    if address is None:
        return inputs, None
    return inputs, "" if address == "local" else address


def _progress(console: Console, enabled: bool) -> Progress:
    return Progress(TextColumn("[progress.description]{task.description}"), BarColumn(), MofNCompleteColumn(),
                    TimeRemainingColumn(), console=console, disable=not enabled, transient=False,
                    auto_refresh=False)  # no refresh thread: the pool forks, and a fork must not copy a held lock
