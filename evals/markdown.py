"""The report as Markdown: the paper's results table with the paper's own figures beside ours, the tests, the
per-module accuracy, and how the numbers were obtained."""

from __future__ import annotations

from typing import Any

from hexar.evals.report import METRICS, PAPER, PAPER_CASES

LABEL = {"hexar": "HEXAR", "end-to-end": "End-to-end", "all-components": "All components"}
METRIC_LABEL = {"root_cause": "Root cause identification", "incorrect_facts": "Presence of incorrect facts",
                "accuracy": "Explanation accuracy"}
ORDER = ("hexar", "end-to-end", "all-components")


def _pct(x: float) -> str:
    return f"{100 * x:.2f}"


def _p(p: float | None) -> str:
    if p is None:
        return "n/a"
    return "< 0.001" if p < 0.001 else f"{p:.3f}"


def results_table(report: dict[str, Any]) -> list[str]:
    summary = report["summary"]
    lines = [
        "| Method | Root cause ↑ | Incorrect facts ↓ | Explanation accuracy ↑ | Runtime (s) ↓ "
        "| Explainer selection ↑ |",
        "|---|---|---|---|---|---|",
    ]
    for m in ORDER:
        paper = PAPER[m]
        sel_paper = f"{int(paper['selection'])}/{PAPER_CASES}" if "selection" in paper else "–"
        if m not in summary:
            why = "n/a (needs an LLM)" if m in report["not_applicable"] else "not run"
            cells = [f"{why} · paper {paper[k]:.2f}" for k in (*METRICS, "runtime_s")]
            lines.append(f"| {LABEL[m]} | " + " | ".join(cells) + f" | {why} · paper {sel_paper} |")
            continue
        s = summary[m]
        cells = [f"**{_pct(s[k]['mean'])}** (σ {s[k]['sd']:.2f}) · paper {paper[k]:.2f}" for k in METRICS]
        rt = s["runtime_s"]
        cells.append(f"**{rt['mean']:.3f}** (σ {rt['sd']:.3f}) · paper {paper['runtime_s']:.2f}")
        sel = s.get("selection")
        cells.append(f"**{sel['correct']}/{sel['n']}** ({_pct(sel['mean'])}) · paper {sel_paper}" if sel else "–")
        lines.append(f"| {LABEL[m]} | " + " | ".join(cells) + " |")
    return lines


def tests_table(report: dict[str, Any]) -> list[str]:
    stats = report["statistics"]
    if not stats["applicable"]:
        return [f"Statistics: {stats['reason']}."]
    lines = ["| Metric | Cochran's Q (df) | p | paper Q | Pairwise McNemar, Holm-corrected p |",
             "|---|---|---|---|---|"]
    for metric in METRICS:
        t = stats["metrics"][metric]
        pairs = "; ".join(f"{LABEL[p['a']]} vs {LABEL[p['b']]}: {_p(p['p_holm'])} {p['mark']}".rstrip()
                          for p in t["pairs"])
        lines.append(f"| {METRIC_LABEL[metric]} | {t['q']:.2f} ({t['df']}) | {_p(t['p'])} | "
                     f"{stats['paper_q'][metric]:.2f} | {pairs} |")
    return lines


def module_table(report: dict[str, Any]) -> list[str]:
    methods = [m for m in ORDER if m in report["summary"]]
    lines = ["| Module | n | " + " | ".join(LABEL[m] for m in methods) + " | Cochran's Q p |",
             "|---|---|" + "---|" * len(methods) + "---|"]
    for module, row in report["per_module"].items():
        test = row["test"]
        p = _p(test["p"]) if test else "n/a"
        lines.append(f"| {module.replace('_', ' ')} | {row['n']} | "
                     + " | ".join(_pct(row["accuracy"][m]) for m in methods) + f" | {p} |")
    return lines


def structured_line(report: dict[str, Any]) -> list[str]:
    s = report["summary"].get("hexar", {}).get("structured")
    if not s:
        return []
    return [f"HEXAR graded on its structured causes instead of its text: root cause {_pct(s['root_cause'])} %, "
            f"incorrect facts {_pct(s['incorrect_facts'])} %, accuracy {_pct(s['accuracy'])} %."]


def judge_lines(report: dict[str, Any]) -> list[str]:
    judge = report.get("judge")
    if not judge:
        return ["No LLM judge ran (`--judge ollama:MODEL` adds one beside the graders)."]
    lines = [f"LLM judge {judge['model']} (rubric {judge['rubric']}) against the deterministic graders "
             "(the paper's annotators disagreed on 0.93 % of root-cause and 1.30 % of incorrect-fact labels):", "",
             "| Method | Label | Judged | Disagreements | Rate |", "|---|---|---|---|---|"]
    for m, rows in judge["agreement"].items():
        for a in rows:
            lines.append(f"| {LABEL.get(m, m)} | {a['label']} | {a['judged']} | {a['disagreements']} | "
                         f"{_pct(a['rate'])} % |")
    return lines


def render(report: dict[str, Any], figures: list[str] | None = None) -> str:
    n = report["summary"][report["methods"][0]]["n"] if report["methods"] else 0
    out = [
        "# HEXAR evaluation", "",
        f"Backend `{report['backend']}`, {n} cases, recordings in `{report['runs']}` (seed {report['seed']}), "
        f"{report['created']}. Ours in bold, the paper's (phi4 14B, 180 cases, human annotators) beside it; "
        "percentages, σ is the standard deviation as the paper reports it.", "",
        *results_table(report), "",
        "## Significance", "", *tests_table(report), "",
        "## Explanation accuracy per module", "", *module_table(report), "",
        "## Grading", "",
        "Deterministic and text-only for every method: a cause counts when the answer affirms one of its "
        "phrasings (`hexar/causes.yaml`), not when it denies it; incorrect facts are affirmed causes other than "
        "the ground truth and the causes also true of the run, blaming the plan when the plan was fine, saying "
        "the task failed when it succeeded, and saying nothing went wrong when something did "
        "(`evals/graders.py`). Runtime is the answering time, without decoding the recording.", "",
        *structured_line(report), "", *judge_lines(report), "",
    ]
    if figures:
        out += ["## Figures", "", *[f"![{f}]({f})" for f in figures], ""]
    out += ["## Prompt hashes", "", *[f"- `{k}` {v}" for k, v in report["prompts"].items()], ""]
    return "\n".join(out)
