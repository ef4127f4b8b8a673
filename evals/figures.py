"""The paper's Fig. 5 (mean per metric and method, with significance marks) and Fig. 6 (explanation accuracy per
module), drawn from a report with matplotlib's Agg backend (no display needed)."""

from __future__ import annotations

import textwrap
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")  # before pyplot loads: robots and CI have no display
import matplotlib.pyplot as plt

from hexar.evals.markdown import LABEL, METRIC_LABEL, ORDER
from hexar.evals.report import METRICS, PAPER

COLOURS = {"hexar": "#2b6cb0", "end-to-end": "#dd6b20", "all-components": "#38a169"}
WIDTH = 0.26


def _marks(ax: Any, x0: float, offsets: dict[str, float], heights: dict[str, float], pairs: list[dict[str, Any]],
           top: float) -> float:
    """Brackets between the bars of significantly different methods; returns the new top."""
    level = top
    for p in pairs:
        if not p["mark"] or p["a"] not in offsets or p["b"] not in offsets:
            continue
        xa, xb = x0 + offsets[p["a"]], x0 + offsets[p["b"]]
        y = max(level, heights[p["a"]], heights[p["b"]]) + 0.04
        ax.plot([xa, xa, xb, xb], [y - 0.015, y, y, y - 0.015], color="black", lw=0.8)
        ax.text((xa + xb) / 2, y, p["mark"], ha="center", va="bottom", fontsize=8)
        level = y + 0.06
    return level


def _offsets() -> dict[str, float]:
    """Every method keeps its slot, run or not, so that the paper's markers and an "n/a" sit where it would be."""
    return {m: (i - (len(ORDER) - 1) / 2) * WIDTH for i, m in enumerate(ORDER)}


def _bars(ax: Any, groups: list[str], values: dict[str, list[float]], tests: list[list[dict[str, Any]]]) -> None:
    offsets = _offsets()
    top = 1.0
    for m in ORDER:
        xs = [g + offsets[m] for g in range(len(groups))]
        if m in values:
            ax.bar(xs, values[m], WIDTH, label=LABEL[m], color=COLOURS[m])
        else:
            for x in xs:
                ax.text(x, 0.02, "n/a", ha="center", va="bottom", fontsize=7, rotation=90, color=COLOURS[m])
    for g in range(len(groups)):
        heights = {m: values[m][g] for m in values}
        if heights:
            top = max(top, _marks(ax, g, offsets, heights, tests[g], max(heights.values())))
    ax.set_xticks(range(len(groups)), groups)
    ax.set_ylim(0, top + 0.08)
    ax.set_yticks([i / 5 for i in range(6)])
    ax.set_xlim(-0.5, len(groups) - 0.5)


def metrics_figure(report: dict[str, Any], path: Path) -> None:
    summary = report["summary"]
    values = {m: [summary[m][k]["mean"] for k in METRICS] for m in ORDER if m in summary}
    stats = report["statistics"]
    tests = [stats["metrics"][k]["pairs"] if stats["applicable"] else [] for k in METRICS]
    fig, ax = plt.subplots(figsize=(7, 4))
    _bars(ax, [textwrap.fill(METRIC_LABEL[k], 18) for k in METRICS], values, tests)
    offsets = _offsets()
    for m in ORDER:
        xs = [g + offsets[m] for g in range(len(METRICS))]
        ax.scatter(xs, [PAPER[m][k] / 100 for k in METRICS], marker="D", s=18, color=COLOURS[m],
                   edgecolors="black", linewidths=0.6, zorder=3, label=f"{LABEL[m]} (paper)")
    ax.set_ylabel("mean")
    marks = "* p<0.05, ** p<0.01, *** p<0.001 (McNemar, Holm)" if stats["applicable"] else "tests not applicable"
    ax.set_title(f"Mean per metric, backend {report['backend']}\n{marks}", fontsize=9)
    ax.legend(fontsize=7, ncol=2, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def modules_figure(report: dict[str, Any], path: Path) -> None:
    rows = report["per_module"]
    names = list(rows)
    values = {m: [rows[n]["accuracy"][m] for n in names] for m in ORDER if m in report["summary"]}
    tests = [rows[n]["test"]["pairs"] if rows[n]["test"] else [] for n in names]
    fig, ax = plt.subplots(figsize=(8, 4))
    _bars(ax, [textwrap.fill(n.replace("_", " "), 12) for n in names], values, tests)
    ax.set_ylabel("mean explanation accuracy")
    ax.set_title(f"Explanation accuracy per module ({report['backend']})", fontsize=9)
    ax.legend(fontsize=7, ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.15))
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)


def draw(report: dict[str, Any], out: Path) -> list[str]:
    """Both figures into `out`; their file names."""
    out.mkdir(parents=True, exist_ok=True)
    metrics_figure(report, out / "fig5_metrics.png")
    modules_figure(report, out / "fig6_modules.png")
    return ["fig5_metrics.png", "fig6_modules.png"]
