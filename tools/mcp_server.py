"""`hexar mcp`: HEXAR's explainers as Model Context Protocol tools, so any MCP client gets grounded answers.

The tools and resources are thin wrappers over `hexar.workspace.Workspace`; one tool per registered explainer is
built from `tool_specs` (tools/explainer_tools.py), the list the agent's LangGraph tools are built from: the same
names and descriptions the router reads.
Imported only by the `hexar mcp` command body: it pulls in the MCP SDK.
"""

from __future__ import annotations

import hmac
import inspect
import logging
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any
from urllib.parse import quote, unquote

from mcp.server.fastmcp import FastMCP
from mcp.server.fastmcp.exceptions import ResourceError, ToolError
from pydantic import Field

from hexar import __version__
from hexar.errors import USER_ERRORS, McpOptionError
from hexar.safe_text import finite_with_warnings, json_dumps
from hexar.workspace import PAGE, Workspace

INSTRUCTIONS = (
    "HEXAR explains what a robot did in a recorded run. Start with list_recordings, pick a recording and a task, "
    "then call the explain_* tool of the module in question (or `ask` for the whole agent). Every answer comes "
    "with evidence: the recorded topic, time (ns) and item that support each cause. Read-only."
)


# What each parameter is, as the client's model reads it in the tool's input schema.
Recording = Annotated[str, Field(description="a recording's path inside the served folder, as list_recordings "
                                             "gives it")]
Offset = Annotated[int, Field(description="where the page starts: 0, then the next_offset the last page returned")]
Limit = Annotated[int, Field(description=f"at most this many entries per call (up to {PAGE})")]
TaskRef = Annotated[str | None, Field(description="a task id, its order number, 'first' or 'latest' (the default)")]
TasksOffset = Annotated[int, Field(description="where the page of task ids starts: 0, then tasks_next_offset")]
Question = Annotated[str, Field(description="the question, as a person asks it (\"why did you stop?\")")]
Thread = Annotated[str | None, Field(description="the thread an earlier answer returned, for a follow-up such as "
                                                 "\"why?\"; none starts a new conversation")]
EvidenceOffset = Annotated[int, Field(description=f"where the page of evidence starts (paged by {PAGE})")]


def _described(text: str) -> str:
    """A docstring as one paragraph: no indentation of its continuation lines, no hard line breaks."""
    return " ".join(inspect.cleandoc(text).split())


def _clean(ws: Workspace, err: Exception) -> str:
    """One line, without the server's own folder in it."""
    return str(err).replace(str(ws.root) + "/", "").replace(str(ws.root), ".").splitlines()[0]


class _OneLine(logging.Filter):
    """The SDK logs a traceback for every failed resource read; a user error is one line, not a traceback."""

    def filter(self, record: logging.LogRecord) -> bool:
        if record.exc_info and isinstance(record.exc_info[1], (*USER_ERRORS, ResourceError)):
            record.exc_info = None
        return True


def build(root: Path, llm: str = "none", host: str = "127.0.0.1", port: int = 8000,
          explainers: Path | None = None) -> FastMCP:
    ws = Workspace(root, llm, explainers)
    logging.getLogger("mcp.server.fastmcp.server").addFilter(_OneLine())
    server = FastMCP("hexar", instructions=INSTRUCTIONS, host=host, port=port, log_level="WARNING")
    server._mcp_server.version = __version__  # what `initialize` reports: HEXAR's version, not the SDK's

    def tool(fn: Callable[..., Any]) -> Callable[..., Any]:
        return server.tool(description=_described(fn.__doc__ or ""))(fn)

    def call(fn: Any, *args: Any, **kwargs: Any) -> dict[str, Any]:
        try:
            result: dict[str, Any] = fn(*args, **kwargs)
        except USER_ERRORS as err:
            raise ToolError(_clean(ws, err)) from err
        # the SDK writes NaN and Infinity into the text content: strict JSON, with a warning where one was
        return dict(finite_with_warnings(result, clean=True))  # values without control or bidi characters

    @tool
    def list_recordings(offset: Offset = 0, limit: Limit = PAGE) -> dict[str, Any]:
        """List the recordings in the served folder (nested folders included) with their tasks: task id,
        instruction, outcome (succeeded, failed, invalid, running, waiting) and the failed skill. Paged; each
        recording shows its first page of tasks and tasks_total; list_tasks pages on."""
        return call(ws.list_recordings, offset, limit)

    @tool
    def list_tasks(recording: Recording, offset: Offset = 0, limit: Limit = PAGE) -> dict[str, Any]:
        """List one recording's tasks (id, order, instruction, outcome, failed skill), at most `limit` per call;
        page on with `offset` = the returned next_offset. A recording without /task_info has one task per Nav2
        navigation goal."""
        return call(ws.list_tasks, recording, offset, limit)

    @tool
    def inspect_task(recording: Recording, task: TaskRef = None, tasks_offset: TasksOffset = 0) -> dict[str, Any]:
        """Show one task of a recording: its plan, each step's status history with times (ns), errors, and the
        time window HEXAR explains. `task`: a task id, its order number, 'first' or 'latest' (default). The ids
        of the recording's tasks come paged: tasks_offset = the returned tasks_next_offset."""
        return call(ws.inspect_task, recording, task, tasks_offset)

    @tool
    def timeline(recording: Recording, offset: Offset = 0, limit: Limit = PAGE) -> dict[str, Any]:
        """The recording's events in time order (task and step status changes, /rosout lines, joystick and
        charging flags), at most `limit` entries per call; page on with `offset` = the returned next_offset."""
        return call(ws.timeline, recording, offset, limit)

    @tool
    def topic_contract(recording: Recording) -> dict[str, Any]:
        """Which topics of the HEXAR topic contract the recording holds, with the expected type, and how many
        messages: whether HEXAR can explain it, and what is missing."""
        return call(ws.contract, recording)

    from hexar.tools.explainer_tools import tool_specs

    def explainer_tool(name: str) -> Any:
        def explain(recording: Recording, question: Question, task: TaskRef = None,
                    evidence_offset: EvidenceOffset = 0) -> dict[str, Any]:
            return call(ws.explain, name, recording, question, task, evidence_offset)

        return explain

    for spec in tool_specs(ws.registry()):
        server.add_tool(explainer_tool(spec.explainer), name=spec.name, description=(
            f"{_described(spec.description)}\n\nArguments: recording (path in the served folder), "
            "question, task (id, order number, 'first' or 'latest'; default latest), evidence_offset (evidence is "
            f"paged by {PAGE}). "
            "Returns the structured explanation: text, causes, evidence (cause, topic, t in ns, item), "
            "counterfactual, fix, details."))

    @tool
    def ask(recording: Recording, question: Question, task: TaskRef = None, thread: Thread = None,
            evidence_offset: EvidenceOffset = 0) -> dict[str, Any]:
        """Ask HEXAR's whole agent one question about a recording: it checks for a failure, routes to the right
        explainer, guards the answer against the evidence, and keeps a conversation. Pass the returned `thread`
        back for follow-ups such as "why?"."""
        return call(ws.ask, recording, question, task, thread, evidence_offset)

    def resource(fn: Any, recording: str) -> str:
        try:
            return json_dumps(fn(unquote(recording)), indent=1, clean=True)
        except USER_ERRORS as err:
            raise ResourceError(_clean(ws, err)) from err

    @server.resource("hexar://recording/{recording}/timeline", mime_type="application/json")
    def timeline_resource(recording: str) -> str:
        """The first page of a recording's timeline (the `timeline` tool pages on). The recording path is
        URL-encoded, e.g. hexar://recording/robot1%2Fbag_3/timeline."""
        return resource(ws.timeline, recording)

    @server.resource("hexar://recording/{recording}/contract", mime_type="application/json")
    def contract_resource(recording: str) -> str:
        """The recording's topic contract report (URL-encoded recording path)."""
        return resource(ws.contract, recording)

    return server


def resource_uri(recording: str, kind: str) -> str:
    return f"hexar://recording/{quote(recording, safe='')}/{kind}"


LOOPBACK = frozenset({"127.0.0.1", "localhost", "::1"})
MIN_TOKEN = 16


class BearerToken:
    """ASGI middleware: every HTTP request must carry `Authorization: Bearer <token>`; 401 otherwise. Off
    loopback anyone on the network (or a web page, by DNS rebinding) could otherwise read the recordings."""

    def __init__(self, app: Any, token: str) -> None:
        self.app, self.expected = app, f"Bearer {token}".encode()

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] == "http":
            got = dict(scope.get("headers") or []).get(b"authorization", b"")
            if not hmac.compare_digest(got, self.expected):
                body = b'{"error": "ERROR: this HEXAR MCP server needs the header Authorization: Bearer <token>"}'
                await send({"type": "http.response.start", "status": 401,
                            "headers": [(b"content-type", b"application/json"), (b"www-authenticate", b"Bearer"),
                                        (b"content-length", str(len(body)).encode())]})
                await send({"type": "http.response.body", "body": body})
                return
        await self.app(scope, receive, send)


def check_http(host: str, token: str | None) -> None:
    """HTTP off loopback needs a token (and says so); a token is long enough to resist guessing."""
    if token is not None and len(token) < MIN_TOKEN:
        raise McpOptionError(f"--token must be at least {MIN_TOKEN} characters (e.g. `openssl rand -hex 16`)")
    if host not in LOOPBACK and not token:
        raise McpOptionError(f"--host {host} lets other machines read these recordings: give --token SECRET "
                             "(or HEXAR_MCP_TOKEN); clients then send the header Authorization: Bearer SECRET")


def serve(root: Path, http: bool, port: int, host: str, llm: str, explainers: Path | None = None,
          token: str | None = None) -> int:
    if http:
        check_http(host, token)
    elif token:
        raise McpOptionError("--token is for --http; a stdio server is reached only by the client that started it")
    server = build(root, llm, host=host, port=port, explainers=explainers)
    if not http:
        server.run("stdio")
        return 0
    import anyio
    import uvicorn

    app: Any = server.streamable_http_app()
    if token:
        app = BearerToken(app, token)
        print(f"HEXAR MCP on http://{host}:{port}/mcp: clients must send Authorization: Bearer <the token>",
              file=sys.stderr, flush=True)
    config = uvicorn.Config(app, host=host, port=port, log_level="warning")
    anyio.run(uvicorn.Server(config).serve)
    return 0
