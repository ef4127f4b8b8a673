"""Does a client asking through `hexar mcp` get what `hexar ask --json` prints?

For each scenario (first variant, the eval's task-specific question) it runs `hexar ask --json --llm none` and the
MCP `ask` tool of one `hexar mcp` server (stdio, the SDK's client), and compares answer text, causes and
explainers. Prints one row per scenario and `same: K/N`; exits 1 when any differs.

    .venv/bin/python scripts/compare_mcp_ask.py [--runs DIR] [--scenario N ...] [--json]
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from mcp import ClientSession, StdioServerParameters
from mcp.client.stdio import stdio_client

from hexar.evals.cases import recording_name, scenario, scenarios

HEXAR = str(Path(sys.executable).with_name("hexar"))
KEYS = ("answer", "causes", "explainers")


def question_of(sid: int) -> str:
    s = scenario(sid)
    return s.questions[1].format(object=s.variants[0].object)


def cli_answer(runs: Path, sid: int) -> dict[str, Any]:
    done = subprocess.run([HEXAR, "ask", str(runs / recording_name(sid, 1)), question_of(sid), "--json",
                           "--llm", "none"], capture_output=True, text=True, check=True,
                          env={**os.environ, "HEXAR_LLM": "none"})
    out: dict[str, Any] = json.loads(done.stdout)
    return out


async def mcp_answers(runs: Path, sids: list[int]) -> dict[int, dict[str, Any]]:
    params = StdioServerParameters(command=HEXAR, args=["mcp", str(runs), "--llm", "none"],
                                   env={**os.environ, "HEXAR_LLM": "none"})
    out: dict[int, dict[str, Any]] = {}
    async with stdio_client(params) as (read, write), ClientSession(read, write) as session:
        await session.initialize()
        for sid in sids:
            result = await session.call_tool("ask", {"recording": recording_name(sid, 1), "question": question_of(sid)})
            if result.isError or result.structuredContent is None:
                out[sid] = {"answer": f"MCP error: {result.content}", "causes": [], "explainers": []}
            else:
                out[sid] = dict(result.structuredContent)
    return out


def compare(runs: Path, sids: list[int]) -> tuple[int, list[dict[str, Any]]]:
    via_mcp = asyncio.run(mcp_answers(runs, sids))
    rows = []
    for sid in sids:
        cli = cli_answer(runs, sid)
        differs = [k for k in KEYS if cli.get(k) != via_mcp[sid].get(k)]
        rows.append({"scenario": sid, "same": not differs, "differs": differs,
                     "causes": cli.get("causes"), "explainers": cli.get("explainers")})
    return sum(r["same"] for r in rows), rows


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=Path, help="folder of bagfile_<s>_1 recordings (simulated when missing)")
    parser.add_argument("--scenario", type=int, action="append", help="only these scenarios (1-20)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    sids = args.scenario or [s.id for s in scenarios()]
    with tempfile.TemporaryDirectory() as tmp:
        runs = args.runs
        if runs is None or not all((runs / recording_name(s, 1)).exists() for s in sids):
            from hexar.evals.scenarios.suite import simulate_suite

            runs = Path(tmp)
            simulate_suite(runs, only=lambda s, v: v == 1 and s in sids)
        same, rows = compare(runs, sids)
    if args.json:
        print(json.dumps({"same": same, "total": len(rows), "rows": rows}))
    else:
        for r in rows:
            mark = "same" if r["same"] else f"DIFFERS in {', '.join(r['differs'])}"
            print(f"scenario {r['scenario']:2d}: {mark}  ({', '.join(r['explainers'] or [])}: "
                  f"{', '.join(r['causes'] or [])})")
        print(f"same: {same}/{len(rows)}")
    return 0 if same == len(rows) else 1


if __name__ == "__main__":
    sys.exit(main())
