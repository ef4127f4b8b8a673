"""The path/timeline figure of one explained task (`--plot FILE.png`, and the page's picture).

Drawn on a bare `Figure` with the Agg canvas, never through pyplot: the page renders figures from server
threads, and pyplot's global state is not thread-safe.
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass, field
from io import BytesIO
from pathlib import Path
from typing import Any

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Ellipse, Rectangle

from hexar.events.log import EventLog
from hexar.events.tasks import Task
from hexar.safe_text import visible
from hexar.web.errors import PlotError
from hexar.web.runview import POOR_COV, SIGMAS, spans, track

STATUS_COLOURS = {"succeeded": "#2e7d32", "failed": "#c62828", "running": "#f9a825", "waiting": "#9e9e9e"}
MAX_ELLIPSES = 60
NS = 1e9


@dataclass
class PathFigure:
    """The figure and the artists a reader checks: the path, its covariance, trips, the stop, the timeline."""

    figure: Figure
    path: Line2D | None = None
    ellipses: list[Ellipse] = field(default_factory=list)
    begins: list[Line2D] = field(default_factory=list)
    ends: list[Line2D] = field(default_factory=list)
    stop: Line2D | None = None
    bars: dict[int, Rectangle] = field(default_factory=dict)
    failure: Line2D | None = None
    evidence: list[Line2D] = field(default_factory=list)
    covariance: Line2D | None = None

    def png(self, dpi: int = 100) -> bytes:
        buf = BytesIO()
        FigureCanvasAgg(self.figure)
        self.figure.savefig(buf, format="png", dpi=dpi)
        return buf.getvalue()

    def save(self, out: Path) -> None:
        try:
            out.write_bytes(self.png())
        except OSError as err:
            raise PlotError(f"cannot write the figure to {out}: {err.strerror or err}") from err


def _draw_path(fig: PathFigure, ax: Any, log: EventLog, task: Task) -> None:
    tr = track(log, task)
    ax.set_title("path from /amcl_pose (2σ covariance)", fontsize=10)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(alpha=0.3)
    if not tr.poses:
        ax.text(0.5, 0.5, "no /amcl_pose during this task", ha="center", va="center", transform=ax.transAxes)
        return
    step = max(1, len(tr.poses) // MAX_ELLIPSES)
    for p in tr.poses[::step]:
        poor = max(p.cov_xy, p.cov_yaw) > POOR_COV
        e = Ellipse((p.x, p.y), 2 * SIGMAS * max(p.cov_x, 0.0) ** 0.5, 2 * SIGMAS * max(p.cov_y, 0.0) ** 0.5,
                    facecolor="#e57373" if poor else "#64b5f6", alpha=0.18, edgecolor="none")
        ax.add_patch(e)
        fig.ellipses.append(e)
    (fig.path,) = ax.plot([p.x for p in tr.poses], [p.y for p in tr.poses], "-", color="#1565c0", lw=1.6,
                          label="path")
    for n, trip in enumerate(tr.trips):
        (b,) = ax.plot(trip.begin.x, trip.begin.y, "o", color="#2e7d32", ms=8,
                       label="trip began" if n == 0 else None)
        (e2,) = ax.plot(trip.end.x, trip.end.y, "s", color="#6a1b9a", ms=7, mfc="none", mew=2,
                        label="trip ended" if n == 0 else None)
        ax.annotate(f"{trip.index + 1}", (trip.begin.x, trip.begin.y), textcoords="offset points",
                    xytext=(5, 5), fontsize=8, parse_math=False)
        fig.begins.append(b)
        fig.ends.append(e2)
    if tr.stop is not None:
        failed = task.failed_skill is not None
        (fig.stop,) = ax.plot(tr.stop.x, tr.stop.y, "X" if failed else "*", color="#c62828" if failed else "#2e7d32",
                              ms=14, label=visible(tr.stop_label).replace("$", r"\$"))  # legends read $…$ as math
    ax.legend(loc="upper left", fontsize=8, framealpha=0.85)


def _draw_timeline(fig: PathFigure, ax: Any, task: Task, evidence_t: list[int]) -> None:
    t0 = task.created
    items = spans(task)
    ax.set_title("skills (status, seconds from the task's start)", fontsize=10)
    for s in items:
        width = max((s.end - s.start) / NS, 0.05)
        bar = ax.barh(s.index, width, left=(s.start - t0) / NS, color=STATUS_COLOURS.get(s.status, "#9e9e9e"),
                      height=0.6)
        fig.bars[s.index] = bar.patches[0]
        ax.text((s.start - t0) / NS, s.index - 0.38, visible(f"{s.skill}: {s.status}"), fontsize=8,
                parse_math=False)
    failed = task.failed_skill
    if failed is not None:
        ft = ((failed.time_of("failed") or failed.last_change) - t0) / NS
        (fig.failure,) = ax.plot(ft, failed.index, "X", color="#b71c1c", ms=12)
        ax.annotate(textwrap.shorten(failed.error_msg or "failed", 60), (ft, failed.index), fontsize=8,
                    textcoords="offset points", xytext=(-4, -13), ha="right", va="top", color="#b71c1c",
                    parse_math=False)
    for n, t in enumerate(evidence_t):
        fig.evidence.append(ax.axvline((t - t0) / NS, color="#ff6f00", ls="--", lw=1,
                                       label="cited evidence" if n == 0 else None))
    ax.set_yticks([s.index for s in items], [str(s.index + 1) for s in items])
    ax.set_ylim(len(items) - 0.4, -0.8)
    ax.set_xlabel("s")
    ax.grid(axis="x", alpha=0.3)
    if evidence_t:
        ax.legend(loc="lower right", fontsize=8)


def _draw_covariance(fig: PathFigure, ax: Any, log: EventLog, task: Task, evidence_t: list[int]) -> None:
    poses = track(log, task).poses
    ax.set_title("localisation uncertainty", fontsize=10)
    ax.set_xlabel("s")
    if not poses:
        return
    t0 = task.created
    (fig.covariance,) = ax.plot([(p.t - t0) / NS for p in poses], [p.cov_xy for p in poses], color="#1565c0",
                                label="mean(cov x, cov y)")
    ax.plot([(p.t - t0) / NS for p in poses], [p.cov_yaw for p in poses], color="#8e24aa", label="cov yaw")
    ax.axhline(POOR_COV, color="#c62828", ls=":", label=f"poor above {POOR_COV}")
    for t in evidence_t:
        ax.axvline((t - t0) / NS, color="#ff6f00", ls="--", lw=1)
    ax.legend(loc="upper left", fontsize=7)
    ax.grid(alpha=0.3)


def build(log: EventLog, task: Task, result: dict[str, Any] | None = None) -> PathFigure:
    """The figure for `task`; `result` (an answer of `hexar ask --json`) adds its answer and evidence times."""
    evidence_t = sorted({int(ev["t"]) for ev in (result or {}).get("evidence", [])})
    # fixed margins, not a layout engine: constrained layout re-measures every text several times, which
    # costs more than drawing an hour of poses
    figure = Figure(figsize=(12, 6.4))
    fig = PathFigure(figure)
    bottom = 0.16 if result and result.get("answer") else 0.09
    grid = figure.add_gridspec(2, 2, width_ratios=[1.05, 1.25], height_ratios=[1.3, 1], left=0.06, right=0.985,
                               top=0.9, bottom=bottom, wspace=0.16, hspace=0.42)
    _draw_path(fig, figure.add_subplot(grid[:, 0]), log, task)
    _draw_timeline(fig, figure.add_subplot(grid[0, 1]), task, evidence_t)
    _draw_covariance(fig, figure.add_subplot(grid[1, 1]), log, task, evidence_t)
    title = f"{log.path.name} · task {task.order}: {task.instruction or '(recovery)'} — {task.outcome}"
    figure.suptitle(textwrap.shorten(visible(title), 110), fontsize=12, parse_math=False, y=0.975)
    if result and result.get("answer"):
        causes = ", ".join(result.get("causes", []))
        said = visible(f"HEXAR: {result['answer']}" + (f"  [{causes}]" if causes else ""), keep_newlines=True)
        text = textwrap.fill(said, 150)
        figure.text(0.01, 0.01, text, fontsize=8.5, va="bottom", parse_math=False, color="#333333")
    return fig
