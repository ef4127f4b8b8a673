"""The batch commands: `eval` (the paper's evaluation and the real-log suites), `mcp` (the explainers to MCP
clients) and `triage` (a fleet's recordings)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from hexar.cli_guard import guarded, out


def eval_(
    runs: Annotated[Path | None, typer.Option(help="folder of the 60 recordings, simulated there when missing "
                                              "[default: ~/.cache/hexar/eval-runs/seed-SEED]")] = None,
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="none, embedded, ollama[:model] or auto "
                                     "(default none: a full LLM run takes hours on a CPU)")] = "none",
    method: Annotated[list[str] | None, typer.Option(help="hexar, end-to-end, all-components [default: all]")] = None,
    scenario: Annotated[list[int] | None, typer.Option(help="only these scenarios (1-20)")] = None,
    module: Annotated[list[str] | None, typer.Option(
        help="only these modules: planning, navigation, ask_human_for_help, text_to_speech, pizza_recommender")] = None,
    kind: Annotated[list[str] | None, typer.Option(help="only these questions: generic, task, observed")] = None,
    first: Annotated[int | None, typer.Option(help="only the first N cases of each scenario")] = None,
    judge: Annotated[str | None, typer.Option(help="an LLM judge beside the graders, e.g. ollama:phi4")] = None,
    audit: Annotated[int, typer.Option(help="print N graded answers beside their grades")] = 0,
    out_dir: Annotated[Path, typer.Option("--out", help="folder for report.json, results.md and the figures")] = Path(
        "eval-out"),
    baseline: Annotated[Path | None, typer.Option(help="exit 1 on a regression against this baseline")] = None,
    write_baseline: Annotated[Path | None, typer.Option(help="write this run as a baseline file")] = None,
    tolerance: Annotated[float, typer.Option(help="allowed metric drop against the baseline (0.02 = 2 points)")] = 0.02,
    seed: Annotated[int, typer.Option(help="simulation seed of recordings that are missing")] = 0,
    resimulate: Annotated[bool, typer.Option(help="simulate the recordings again even if present")] = False,
    figures: Annotated[bool, typer.Option(help="draw the PNG figures")] = True,
    suite: Annotated[str, typer.Option(help="paper (the 180 cases), real-nav2 (real Nav2 logs from public "
                                       "threads), real-nav2-heldout (threads never tuned on), real-nav2-blind, "
                                       "real-nav2-blind2 ... -blind29 (blind sets), real-modules, "
                                       "real-modules-heldout, -heldout2 ... -heldout36 (MoveIt 2, "
                                       "ros2_control, bring-up); the real-nav2 "
                                       "suites use --out, --runs, --llm, --baseline, --write-baseline, "
                                       "--tolerance")] = "paper",
    cases: Annotated[Path | None, typer.Option(help="your own excerpts, a YAML file in the format of the "
                                               "real-nav2 or real-modules data (their README.md), run with "
                                               "--suite real-nav2 or --suite real-modules")] = None,
) -> None:
    """Reproduce the paper's evaluation: 180 cases x HEXAR and both baselines, graded, tested, plotted."""

    def body() -> int:
        if suite.startswith("real-modules"):
            from hexar.evals.real_modules_cli import real_modules_main

            return real_modules_main(suite, out_dir, runs, llm, out,
                                     others={"--method": method, "--scenario": scenario, "--module": module,
                                             "--kind": kind, "--first": first, "--judge": judge,
                                             "--audit": audit or None, "--baseline": baseline,
                                             "--write-baseline": write_baseline}, cases=cases)
        if suite != "paper":
            from hexar.evals.real_nav2_cli import real_nav2_main

            return real_nav2_main(suite, out_dir, runs, llm, baseline, write_baseline, tolerance, out,
                                  paper_only={"--method": method, "--scenario": scenario, "--module": module,
                                              "--kind": kind, "--first": first, "--judge": judge,
                                              "--audit": audit or None}, cases=cases)
        from hexar.errors import HexarError
        from hexar.evals.cli import EvalOptions, eval_command

        if cases is not None:
            raise HexarError("--cases goes with --suite real-nav2 or --suite real-modules, not the paper's suite")
        opts = EvalOptions(
            out=out_dir, runs=runs, llm=llm, methods=tuple(method or ()), scenarios=tuple(scenario or ()),
            modules=tuple(module or ()), kinds=tuple(kind or ()), first=first, judge=judge, audit=audit,
            baseline=baseline, write_baseline=write_baseline, tolerance=tolerance, seed=seed,
            resimulate=resimulate, figures=figures,
        )
        return eval_command(opts, out)

    raise typer.Exit(guarded(body))


def mcp(
    folder: Annotated[Path, typer.Argument(help="serve the recordings under this folder (read-only)")] = Path("."),
    http: Annotated[bool, typer.Option("--http", help="streamable HTTP instead of stdio")] = False,
    port: Annotated[int, typer.Option(help="HTTP port")] = 8000,
    host: Annotated[str, typer.Option(help="HTTP address to listen on")] = "127.0.0.1",
    llm: Annotated[str, typer.Option(envvar="HEXAR_LLM", help="the `ask` tool's LLM: auto, embedded, "
                                     "ollama[:model] or none")] = "auto",
    explainers: Annotated[Path | None, typer.Option(help="a modules.toml registering more explainers")] = None,
    token: Annotated[str | None, typer.Option(envvar="HEXAR_MCP_TOKEN", help="with --http: every request must "
                                              "send Authorization: Bearer TOKEN (required off loopback)")] = None,
) -> None:
    """Serve HEXAR's explainers to any MCP client (Claude Desktop, the mcp inspector): stdio or HTTP."""

    def body() -> int:
        from hexar.inputs import port_number
        from hexar.tools.mcp_server import serve

        if http:
            port_number(port)
        return serve(folder, http, port, host, llm, explainers, token)

    raise typer.Exit(guarded(body))


def triage(
    inputs: Annotated[list[str] | None, typer.Argument(help="folders (nested by robot/date) or globs of recordings")]
    = None,
    out_dir: Annotated[Path, typer.Option("--out", help="results, tables, report, figures")] = Path("triage-out"),
    workers: Annotated[int | None, typer.Option(help="processes [default: the machine's cores]")] = None,
    ray: Annotated[bool, typer.Option("--ray", help="run as Ray tasks, on a local Ray instance unless an address "
                                      "follows (--ray auto, --ray ray://host:10001)")] = False,
    ray_address: Annotated[str | None, typer.Option(help="the Ray cluster to run on (implies --ray)")] = None,
    compare: Annotated[tuple[str, str] | None, typer.Option(help="compare two triage outputs or two day ranges "
                                                            "(YYYY-MM-DD[..YYYY-MM-DD]) of --out")] = None,
    figures: Annotated[bool, typer.Option(help="draw the PNG figures")] = True,
) -> None:
    """Explain every task of many recordings without an LLM: tables, a report of causes, resumable, or on Ray."""

    def body() -> int:
        from hexar.errors import HexarError

        if compare is not None:
            from hexar.fleet.compare import compare as run_compare
            from hexar.fleet.compare import compare_markdown

            text = compare_markdown(run_compare(compare[0], compare[1], out_dir))
            print(text)
            return 0
        if not inputs:
            raise HexarError("give folders or globs of recordings, or --compare A B")
        from hexar.fleet.command import TriageOptions, ray_target, triage_command

        given, where = ray_target(inputs, ray, ray_address)
        if not given:
            raise HexarError("give folders or globs of recordings, or --compare A B")
        return triage_command(TriageOptions(tuple(given), out_dir, workers, where, figures), out)

    raise typer.Exit(guarded(body))

