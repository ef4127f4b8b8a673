"""The fuzz harness's other ways in: the web page's HTTP API (a real server on 127.0.0.1) and the MCP tools
(the real FastMCP server, called in-process), over the same hostile recording and question as the CLI.

Properties: every answer is strict JSON with a status the page handles (200, 400, 404), every string VALUE in
it free of control and invisible characters, no absolute path of the served folder in it, no traceback; every
MCP refusal one line; every answered cause backed by recorded evidence.
"""

from __future__ import annotations

import asyncio
import http.client
import json
import random
import threading
from pathlib import Path
from typing import Any
from urllib.parse import quote

from hexar.events.log import EventLog
from tests.fuzz.harness import Outcome, _bad_char, _strict, grounded


def strings_of(value: Any) -> list[str]:
    if isinstance(value, dict):
        return [s for k, v in value.items() for s in (*strings_of(k), *strings_of(v))]
    if isinstance(value, list):
        return [s for v in value for s in strings_of(v)]
    return [value] if isinstance(value, str) else []


def _check_json(o: Outcome, text: str, folder: Path) -> Any:
    try:
        data = _strict(text)
    except ValueError as e:
        o.problems.append(f"invalid JSON: {e}")
        return None
    bad = next((b for s in strings_of(data) if (b := _bad_char(s))), None)
    if bad:
        o.problems.append(f"raw control character {bad} in a JSON value")
    if str(folder.resolve()) in text or str(folder) in text:
        o.problems.append("absolute path of the served folder in the answer")
    if "Traceback (most recent call last)" in text:  # a hostile recording may say "Traceback" itself
        o.problems.append("traceback in the answer")
    return data


def web(folder: Path, bag: Path, question: str, log: EventLog | None) -> Outcome:
    from hexar.web.server import make_server
    from hexar.web.store import Store

    o = Outcome(["web", str(bag)], 0, "", "")
    server = make_server(Store(folder, "none", folder / "web.sqlite"), "127.0.0.1", 0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    port = server.server_address[1]
    name = quote(bag.name)
    body = json.dumps({"name": bag.name, "question": question}, ensure_ascii=False).encode("utf-8", "surrogatepass")
    requests: list[tuple[str, str, bytes | None]] = [
        ("GET", "/api/runs", None), ("GET", f"/api/run?name={name}", None), ("GET", f"/api/lines?name={name}", None),
        ("GET", f"/api/plot.png?name={name}", None), ("POST", "/api/chat", body)]
    try:
        for method, path, data in requests:
            conn = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
            try:
                conn.request(method, path, body=data, headers={"Content-Type": "application/json"})
                r = conn.getresponse()
                raw = r.read()
            finally:
                conn.close()
            if r.status not in (200, 400, 404):
                o.problems.append(f"{method} {path}: status {r.status}: {raw[:200]!r}")
            if r.getheader("Content-Type") != "application/json":
                continue
            answer = _check_json(o, raw.decode("utf-8", "replace"), folder)
            if path == "/api/chat" and r.status == 200 and isinstance(answer, dict) and not answer.get("error"):
                if log is None:
                    o.problems.append("the page answered about a recording that cannot be read")
                else:
                    o.problems += grounded(answer, log)
    finally:
        server.shutdown()
        server.server_close()
    o.code = 2 if o.problems else 0
    return o


def mcp(folder: Path, bag: Path, question: str, rng: random.Random) -> Outcome:
    from mcp.server.fastmcp.exceptions import ToolError

    from hexar.tools.mcp_server import build

    o = Outcome(["mcp", str(bag)], 0, "", "")
    server = build(folder, "none")
    rec = bag.name
    calls: list[tuple[str, dict[str, Any]]] = [
        ("list_recordings", {}), ("inspect_task", {"recording": rec}), ("timeline", {"recording": rec}),
        ("topic_contract", {"recording": rec}), ("ask", {"recording": rec, "question": question}),
        (rng.choice(["explain_navigation", "explain_planning", "explain_speech", "explain_asking_for_help",
                     "explain_pizza_choice"]), {"recording": rec, "question": question})]

    async def go() -> None:
        for tool, args in calls:
            try:
                result: Any = await server.call_tool(tool, args)
            except ToolError as err:
                text = str(err)
                if "\n" in text or "Traceback (most recent" in text or str(folder.resolve()) in text:
                    o.problems.append(f"{tool}: refusal is not one clean line: {text[:200]!r}")
                if (b := _bad_char(text)) is not None:
                    o.problems.append(f"{tool}: raw control character {b} in the refusal")
                continue
            blocks = result[0] if isinstance(result, tuple) else result
            for block in blocks if isinstance(blocks, list | tuple) else []:
                _check_json(o, getattr(block, "text", "null"), folder)

    asyncio.run(go())
    o.code = 2 if o.problems else 0
    return o
