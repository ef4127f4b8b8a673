"""`hexar web`: the page, served by the standard library's HTTP server from the installed package.

Loopback by default. The server has no authentication: it reads the recordings of one folder and the
conversation file, and the agent it drives is read-only, but anyone who can reach the port can read the runs.
"""

from __future__ import annotations

import json
import sys
import traceback
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlparse

from hexar.errors import USER_ERRORS
from hexar.web.live import LiveSource
from hexar.web.store import Store

STATIC = {"index.html": "text/html; charset=utf-8", "app.js": "text/javascript; charset=utf-8",
          "style.css": "text/css; charset=utf-8"}
# The page's other ES modules (app.js imports them; a module script must come with a JavaScript type)
STATIC |= {f"{name}.js": STATIC["app.js"] for name in ("common", "runs", "run", "timeline", "path", "cards", "chat")}
MAX_BODY = 64 * 1024
# The page's own script and style only: a recorded string that slipped into markup still could not run.
CSP = "default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; object-src 'none'"


def static_file(name: str) -> bytes:
    return resources.files("hexar.web").joinpath("static", name).read_bytes()


class Handler(BaseHTTPRequestHandler):
    store: Store
    server_version = "hexar-web"

    def log_message(self, format: str, *args: Any) -> None:
        if getattr(self.server, "verbose", False):
            super().log_message(format, *args)

    def _send(self, status: int, body: bytes, ctype: str) -> None:
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Content-Security-Policy", CSP)
        self.end_headers()
        self.wfile.write(body)

    def _json(self, data: Any, status: int = 200) -> None:
        from hexar.safe_text import json_dumps  # strict JSON: a NaN from a recording becomes null, with a warning

        self._send(status, json_dumps(data).encode(), "application/json")

    def _guard(self, fn: Any) -> None:
        """A user error becomes the CLI's one-line message; anything else a short line, never a traceback."""
        try:
            fn()
        except USER_ERRORS as e:
            self._json({"error": f"ERROR: {e}"}, HTTPStatus.BAD_REQUEST)
        except (BrokenPipeError, ConnectionResetError):
            pass
        except Exception:
            traceback.print_exc(file=sys.stderr)
            self._json({"error": "ERROR: the server failed on this request (its terminal shows why)"},
                       HTTPStatus.INTERNAL_SERVER_ERROR)

    def do_GET(self) -> None:
        url = urlparse(self.path)
        q = {k: v[-1] for k, v in parse_qs(url.query).items()}
        s = self.store

        def body() -> None:
            if url.path in {"/", "/index.html"}:
                self._send(200, static_file("index.html"), STATIC["index.html"])
            elif url.path.startswith("/static/") and url.path.removeprefix("/static/") in STATIC:
                name = url.path.removeprefix("/static/")
                self._send(200, static_file(name), STATIC[name])
            elif url.path == "/api/runs":
                self._json(s.runs())
            elif url.path == "/api/run":
                self._json(s.run(q.get("name", ""), q.get("task"), q.get("since")))
            elif url.path == "/api/lines":
                self._json(s.lines(q.get("name", ""), q.get("task")))
            elif url.path == "/api/plot.png":
                self._send(200, s.plot(q.get("name", ""), q.get("task")), "image/png")
            elif url.path == "/api/backend":
                self._json({"backend": s.backend().name})
            elif url.path == "/api/history":
                self._json({"history": s.history(q.get("name", ""), q.get("thread", ""))})
            else:
                self._json({"error": f"ERROR: no such page: {url.path}"}, HTTPStatus.NOT_FOUND)

        self._guard(body)

    def do_POST(self) -> None:
        def body() -> None:
            if urlparse(self.path).path != "/api/chat":
                self._json({"error": "ERROR: no such endpoint"}, HTTPStatus.NOT_FOUND)
                return
            size = int(self.headers.get("Content-Length") or 0)
            if size > MAX_BODY:
                self._json({"error": "ERROR: question too long"}, HTTPStatus.REQUEST_ENTITY_TOO_LARGE)
                return
            try:
                data = json.loads(self.rfile.read(size) or b"{}")
            except (json.JSONDecodeError, UnicodeDecodeError):
                self._json({"error": "ERROR: the request is not JSON"}, HTTPStatus.BAD_REQUEST)
                return
            result = self.store.ask(str(data.get("name", "")), str(data.get("question", "")),
                                    data.get("thread") or None, data.get("task") or None)
            self._json(result)

        self._guard(body)


def make_server(store: Store, host: str = "127.0.0.1", port: int = 8080) -> ThreadingHTTPServer:
    handler = type("HexarHandler", (Handler,), {"store": store})
    server = ThreadingHTTPServer((host, port), handler)
    server.daemon_threads = True
    return server


def live_source(live: bool, domain: int | None) -> LiveSource | None:
    """`--live [--domain N]`: the robot's topics, read-only over DDS (the transport `hexar serve --transport dds`
    uses; no rclpy here, since the page writes nothing and needs no ROS graph presence)."""
    from hexar.web.errors import WebError

    if not live:
        if domain is not None:
            raise WebError("--domain needs --live (it picks the robot's DDS domain)")
        return None
    from hexar.live.commands import domain_id

    return LiveSource.over_dds(domain_id(domain))


def serve(root: Path | None, host: str, port: int, llm: str, checkpoints: Path | None, live: bool = False,
          domain: int | None = None) -> int:
    from hexar.web.errors import WebError

    if root is None and not live:
        root = Path(".")
    source = live_source(live, domain)
    try:
        store = Store(root, llm, checkpoints, source)
        store.backend()  # an unreachable model is the command's one-line error, not a broken chat later
        try:
            server = make_server(store, host, port)
        except OSError as err:
            raise WebError(f"cannot listen on {host}:{port}: {err.strerror or err}") from err
    except BaseException:
        if source is not None:
            source.close()
        raise
    where = f"http://{host}:{server.server_address[1]}/"
    what = [f"recordings in {root}"] if root is not None else []
    if source is not None and source.watcher is not None:
        what.append(f"the live robot on DDS domain {source.watcher.domain_id}")
    print(f"HEXAR web: {where}  ({' and '.join(what)}; backend {store.backend().name}; Ctrl-C stops)", flush=True)
    if host not in {"127.0.0.1", "localhost", "::1"}:
        print(f"warning: listening on {host}: anyone who can reach this port can read these runs", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
        store.close()
    return 0
