"""`hexar mcp` as a client sees it: the server runs as a subprocess and the MCP SDK's own client talks to it over
stdio and streamable HTTP."""

from __future__ import annotations

import asyncio
import json
import os
import shutil
import socket
import subprocess
import sys
import time
from collections.abc import AsyncIterator, Awaitable, Callable
from contextlib import asynccontextmanager
from pathlib import Path
from typing import Any

import pytest
from mcp import ClientSession, StdioServerParameters
from mcp.client.stdio import stdio_client
from mcp.client.streamable_http import streamable_http_client
from mcp.shared.exceptions import McpError

from hexar.evals.cases import scenario
from hexar.events import EventLog, read_recording
from hexar.events import contract as c
from hexar.explainers.registry import Registry
from hexar.tools.explainer_tools import tools_for
from hexar.tools.mcp_server import resource_uri

ROOT = Path(__file__).resolve().parents[2]
HEXAR = str(Path(sys.executable).with_name("hexar"))
# One failed (or, for the pizza, explained) run per module, with the tool the client would pick.
PER_MODULE = {1: "explain_planning", 5: "explain_navigation", 11: "explain_asking_for_help", 19: "explain_speech",
              20: "explain_pizza_choice"}


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder as a robot team keeps it: runs nested by robot, one corrupt recording, one link leading out."""
    from hexar.evals.scenarios.suite import simulate_suite

    base = tmp_path_factory.mktemp("served")
    root = base / "fleet"
    simulate_suite(root / "tiago-1", only=lambda s, v: v == 1 and s in PER_MODULE)
    simulate_suite(base / "elsewhere", only=lambda s, v: s == 6 and v == 1)
    bad = root / "tiago-2" / "broken"
    shutil.copytree(root / "tiago-1" / "bagfile_5_1", bad)
    db = next(bad.glob("*.db3"))
    db.write_bytes(db.read_bytes()[:4096])
    (root / "tiago-2" / "sneaky").symlink_to(base / "elsewhere" / "bagfile_6_1")
    return root


def _env() -> dict[str, str]:
    return {**os.environ, "PYTHONPATH": str(ROOT), "HEXAR_LLM": "none"}


@asynccontextmanager
async def stdio_session(folder: Path, *extra: str) -> AsyncIterator[ClientSession]:
    params = StdioServerParameters(command=HEXAR, args=["mcp", str(folder), "--llm", "none", *extra],
                                   env=_env(), cwd=str(ROOT))
    async with stdio_client(params) as (read, write), ClientSession(read, write) as session:
        await session.initialize()
        yield session


def run(fn: Callable[[], Awaitable[None]]) -> None:
    asyncio.run(fn())  # type: ignore[arg-type]


async def call(session: ClientSession, tool: str, **args: Any) -> dict[str, Any]:
    result = await session.call_tool(tool, args)
    assert not result.isError, result.content
    assert result.structuredContent is not None
    return result.structuredContent


async def error_of(session: ClientSession, tool: str, **args: Any) -> str:
    result = await session.call_tool(tool, args)
    assert result.isError
    text = result.content[0].text  # type: ignore[union-attr]
    assert "\n" not in text and "Traceback" not in text
    return str(text)


def recorded_times(log: EventLog, topic: str) -> set[int]:
    if topic == c.ROSOUT:
        return {line.t for line in log.logs}
    if topic == c.AMCL_POSE:
        return {p.t for p in log.poses}
    if topic == c.TASK_INFO:
        return {u.t for u in log.task_updates}
    return {r.t for r in log.statuses.get(topic, [])} | {s.t for s in log.flags.get(topic, [])}


def test_tools_explain_a_failed_run_per_module_with_evidence_from_the_recording(served: Path) -> None:
    async def go() -> None:
        async with stdio_session(served) as s:
            tools = {t.name: t for t in (await s.list_tools()).tools}
            assert set(PER_MODULE.values()) | {"list_recordings", "inspect_task", "ask", "timeline"} <= set(tools)
            for agent_tool in tools_for(Registry.load()):  # the agent's router reads the same descriptions
                said = " ".join(agent_tool.description.split())  # the same words, as one paragraph
                assert said in (tools[agent_tool.name].description or "")
            listing = await call(s, "list_recordings")
            names = {r["recording"]: r for r in listing["recordings"]}
            assert "tiago-1/bagfile_5_1" in names and names["tiago-1/bagfile_5_1"]["tasks"][0]["outcome"] == "failed"
            assert "cannot read" in names["tiago-2/broken"]["error"]
            assert "tiago-2/sneaky" not in names  # the walk does not follow a link out of the folder
            for sid, tool in PER_MODULE.items():
                rec = f"tiago-1/bagfile_{sid}_1"
                question = scenario(sid).questions[1].format(object=scenario(sid).variants[0].object)
                exp = await call(s, tool, recording=rec, question=question, task="first")
                assert scenario(sid).cause in exp["causes"], (sid, exp)
                assert exp["text"] and exp["evidence"] and exp["evidence_total"] >= len(exp["evidence"])
                log = read_recording(served / rec)
                for ev in exp["evidence"]:
                    assert ev["t"] in recorded_times(log, ev["topic"]), (sid, ev)
                    if ev["topic"] == c.ROSOUT:
                        assert ev["item"] in {line.render() for line in log.logs}
            task = await call(s, "inspect_task", recording="tiago-1/bagfile_5_1", task="1")
            assert task["outcome"] == "failed" and task["skills"][0]["status"] == "failed"
            assert [h["status"] for h in task["skills"][0]["history"]] == ["waiting", "Running", "failed"]

    run(go)


BAD = [
    ("explain_navigation", {"recording": "nope", "question": "What happened?"}, "no recording 'nope'"),
    ("explain_navigation", {"recording": "../elsewhere/bagfile_6_1", "question": "What happened?"}, "outside"),
    ("explain_navigation", {"recording": "/etc", "question": "What happened?"}, "outside"),
    ("inspect_task", {"recording": "tiago-2/sneaky"}, "outside"),  # a link inside that leads out
    ("inspect_task", {"recording": "tiago-1"}, "is not a recording"),
    ("inspect_task", {"recording": "tiago-1/bagfile_5_1", "task": "zzz"}, "no task 'zzz'"),
    ("explain_navigation", {"recording": "tiago-2/broken", "question": "What happened?"}, "cannot read"),
    ("explain_navigation", {"recording": "tiago-1/bagfile_5_1", "question": ""}, "empty question"),
    ("ask", {"recording": "tiago-1/bagfile_5_1", "question": "asdf qwer zxcv"}, "I don't understand"),
    ("ask", {"recording": "tiago-2/broken", "question": "What happened?"}, "cannot read"),
    ("timeline", {"recording": "tiago-1/bagfile_5_1", "offset": -1}, "offset must be"),
    ("timeline", {"recording": "tiago-1/bagfile_5_1", "limit": 10_000}, "limit must be"),
]


def test_bad_input_is_an_mcp_error_and_the_server_lives_on(served: Path) -> None:
    async def go() -> None:
        async with stdio_session(served) as s:
            for tool, args, message in BAD:
                text = await error_of(s, tool, **args)
                assert message in text, (tool, args, text)
                assert str(served) not in text  # the server's own folder is not shown to the client
            after = await call(s, "list_recordings", limit=1)  # still serving
            assert after["total"] == 6 and after["next_offset"] == 1

    run(go)


def test_paging_resources_and_ask_threads(served: Path) -> None:
    async def go() -> None:
        async with stdio_session(served) as s:
            rec = "tiago-1/bagfile_5_1"
            first = await call(s, "timeline", recording=rec, limit=50)
            total = first["total"]
            assert total > 50 and len(first["entries"]) == 50
            seen = list(first["entries"])
            while (nxt := first["next_offset"]) is not None:
                first = await call(s, "timeline", recording=rec, offset=nxt, limit=50)
                assert len(first["entries"]) <= 50
                seen += first["entries"]
            assert len(seen) == total and [e["t"] for e in seen] == sorted(e["t"] for e in seen)
            assert any("Failed to make progress" in e["item"] for e in seen)

            page = json.loads((await s.read_resource(resource_uri(rec, "timeline"))).contents[0].text)  # type: ignore[union-attr]
            assert page["entries"] == seen[:50]
            contract = json.loads((await s.read_resource(resource_uri(rec, "contract"))).contents[0].text)  # type: ignore[union-attr]
            status = {row["topic"]: row["status"] for row in contract["contract"]}
            assert status[c.TASK_INFO] == "ok" and status[c.ROSOUT] == "ok" and contract["explainable"]
            with pytest.raises(McpError, match="outside"):
                await s.read_resource(resource_uri("../elsewhere/bagfile_6_1", "contract"))
            with pytest.raises(McpError, match="cannot read"):
                await s.read_resource(resource_uri("tiago-2/broken", "timeline"))

            answer = await call(s, "ask", recording=rec, question="Why didn't you bring me the coffee?")
            assert answer["route"] == "failure_check" and "navigation.blocked_path" in answer["causes"]
            deeper = await call(s, "ask", recording=rec, question="why?", thread=answer["thread"])
            assert deeper["thread"] == answer["thread"] and deeper["intent"] == "deeper"
            assert deeper["answer"] != answer["answer"]

    run(go)


def test_a_sixth_registered_explainer_is_a_sixth_tool(served: Path, tmp_path: Path) -> None:
    cfg = tmp_path / "modules.toml"
    cfg.write_text('[explainers]\ndiagnostics = "tests.explainers.test_registry:DiagnosticsExplainer"\n'
                   '[modules]\nself_check = ["diagnostics"]\n')

    async def go() -> None:
        async with stdio_session(served, "--explainers", str(cfg)) as s:
            tools = {t.name: t for t in (await s.list_tools()).tools}
            assert "Hardware diagnostics" in (tools["explain_diagnostics"].description or "")
            exp = await call(s, "explain_diagnostics", recording="tiago-1/bagfile_5_1", question="What happened?")
            assert exp["explainer"] == "diagnostics" and exp["causes"] == ["diagnostics.report"]

    run(go)


def _free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def test_streamable_http(served: Path) -> None:
    port = _free_port()
    proc = subprocess.Popen([HEXAR, "mcp", str(served), "--http", "--port", str(port), "--llm", "none"],
                            env=_env(), cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            with socket.socket() as sock:
                if sock.connect_ex(("127.0.0.1", port)) == 0:
                    break
            assert proc.poll() is None, proc.stderr.read() if proc.stderr else ""
            time.sleep(0.2)

        async def go() -> None:
            async with streamable_http_client(f"http://127.0.0.1:{port}/mcp") as (read, write, _), \
                    ClientSession(read, write) as s:
                await s.initialize()
                exp = await call(s, "explain_asking_for_help", recording="tiago-1/bagfile_11_1",
                                 question="Why didn't you bring me the coffee?")
                assert "ask_human.nobody_detected" in exp["causes"]
                assert "outside" in await error_of(s, "inspect_task", recording="../elsewhere/bagfile_6_1")

        run(go)
    finally:
        proc.terminate()
        proc.wait(timeout=10)


def test_the_mcp_answer_equals_hexar_ask_json(served: Path) -> None:
    """The `ask` tool is the same agent as `hexar ask --json` (scripts/compare_mcp_ask.py runs all 20)."""
    done = subprocess.run([sys.executable, str(ROOT / "scripts" / "compare_mcp_ask.py"), "--runs",
                           str(served / "tiago-1"), "--scenario", "5", "--scenario", "19", "--json"],
                          capture_output=True, text=True, env=_env(), timeout=300)
    report = json.loads(done.stdout)
    assert done.returncode == 0 and report["same"] == report["total"] == 2, report


def test_hexar_mcp_on_a_missing_folder_is_one_line(tmp_path: Path) -> None:
    done = subprocess.run([HEXAR, "mcp", str(tmp_path / "nope")], capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and done.stderr.startswith("ERROR: not a folder") and done.stderr.count("\n") == 1


def test_tools_read_cleanly_and_the_server_is_hexar(served: Path) -> None:
    """Descriptions as one paragraph each (no docstring indentation), every parameter described, and the
    server named with HEXAR's version, not the SDK's."""
    from hexar import __version__

    async def go() -> None:
        params = StdioServerParameters(command=HEXAR, args=["mcp", str(served), "--llm", "none"], env=_env(),
                                       cwd=str(ROOT))
        async with stdio_client(params) as (read, write), ClientSession(read, write) as s:
            info = await s.initialize()
            assert info.serverInfo.name == "hexar" and info.serverInfo.version == __version__
            for tool in (await s.list_tools()).tools:
                assert tool.description and "\n    " not in tool.description, tool.name
                props = tool.inputSchema["properties"]
                assert props and all(p.get("description") for p in props.values()), tool.name

    run(go)
