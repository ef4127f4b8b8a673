"""The Ollama backend against a loopback HTTP server that replays an Ollama /api/chat exchange.

No Ollama server can run here; the replay follows Ollama's documented /api/chat wire format (NDJSON stream,
tool calls in `message.tool_calls`). It fakes only the network boundary: ChatOllama, the ollama client and
the agent are all real.
"""

from __future__ import annotations

import json
import threading
from collections.abc import Iterator
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any, ClassVar

import pytest

from hexar.agent.backends import resolve
from hexar.agent.context import RunSettings
from hexar.agent.session import Session

STAMP = "2026-11-20T10:00:00.000000Z"


def _chunks(request: dict[str, Any]) -> list[dict[str, Any]]:
    model = request["model"]
    done = {"model": model, "created_at": STAMP, "message": {"role": "assistant", "content": ""}, "done": True,
            "done_reason": "stop", "total_duration": 512000000, "load_duration": 1000000,
            "prompt_eval_count": 210, "prompt_eval_duration": 90000000, "eval_count": 24,
            "eval_duration": 400000000}
    if request.get("tools"):
        call = {"function": {"name": "explain_navigation", "arguments": {"question": "why so slow"}}}
        return [{"model": model, "created_at": STAMP,
                 "message": {"role": "assistant", "content": "", "tool_calls": [call]}, "done": False}, done]
    words = ["I ", "reached ", "the ", "kitchen ", "slowly ", "because ", "people ", "kept ", "crossing ",
             "my ", "path, ", "so ", "I ", "had ", "to ", "replan."]
    return [{"model": model, "created_at": STAMP, "message": {"role": "assistant", "content": w}, "done": False}
            for w in words] + [done]


class Replay(BaseHTTPRequestHandler):
    requests: ClassVar[list[dict[str, Any]]] = []

    def log_message(self, *args: Any) -> None:
        pass

    def do_GET(self) -> None:
        body = json.dumps({"models": [{"name": "phi4:latest", "model": "phi4:latest"}]}).encode()
        self.send_response(200)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def do_POST(self) -> None:
        request = json.loads(self.rfile.read(int(self.headers["Content-Length"])))
        Replay.requests.append(request)
        chunks = _chunks(request)
        if request.get("stream", True):
            body = b"".join(json.dumps(c).encode() + b"\n" for c in chunks)
            content_type = "application/x-ndjson"
        else:
            final = dict(chunks[-1])
            final["message"] = {"role": "assistant",
                                "content": "".join(c["message"]["content"] for c in chunks),
                                **({"tool_calls": chunks[0]["message"]["tool_calls"]}
                                   if "tool_calls" in chunks[0]["message"] else {})}
            body = json.dumps(final).encode()
            content_type = "application/json"
        self.send_response(200)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)


@pytest.fixture
def ollama(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    server = ThreadingHTTPServer(("127.0.0.1", 0), Replay)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    host = f"http://127.0.0.1:{server.server_address[1]}"
    monkeypatch.setenv("OLLAMA_HOST", host)
    Replay.requests = []
    yield host
    server.shutdown()


def test_auto_prefers_a_reachable_ollama(ollama: str) -> None:
    assert resolve("auto").name == "ollama:phi4"
    assert resolve("ollama:llama3.2").name == "ollama:llama3.2"


def test_router_uses_native_tool_calls_and_answer_is_phrased(ollama: str, suite: Path) -> None:
    session = Session(RunSettings(recording=suite / "bagfile_9_1", llm="ollama:phi4"))
    result = session.ask("Why did it take you so long to bring me the coffee?")
    assert result["backend"] == "ollama:phi4"
    assert result["route"] == "llm" and result["explainers"] == ["navigation"]
    tool_requests = [r for r in Replay.requests if r.get("tools")]
    assert tool_requests and {t["function"]["name"] for t in tool_requests[0]["tools"]} >= {"explain_navigation"}
    assert result["answer"] == "I reached the kitchen slowly because people kept crossing my path, so I had to replan."
    assert result["phrased_by"] == ["ollama:phi4"] and result["fallback"] == []
    assert all(r["options"]["temperature"] == 0 for r in Replay.requests)


def test_failure_check_skips_the_router_call(ollama: str, suite: Path) -> None:
    session = Session(RunSettings(recording=suite / "bagfile_6_1", llm="ollama:phi4"))
    result = session.ask("Why didn't you bring me the coffee?")
    assert result["route"] == "failure_check"
    assert not [r for r in Replay.requests if r.get("tools")]
    # the replayed phrasing talks about people crossing, which the joystick finding does not support
    assert result["fallback"] and "joystick" in result["answer"].lower()
