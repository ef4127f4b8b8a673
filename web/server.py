"""`hexar web`: the page, served by the standard library's HTTP server from the installed package.

Loopback by default. The server has no authentication: it reads the recordings of one folder and the
conversation file, and the agent it drives is read-only, but anyone who can reach the port can read the runs.
Other web sites cannot: a request must name this server in its Host header (no DNS rebinding), a question must
come as JSON from the page's own origin (no cross-site form or text/plain post), and the page cannot be framed.
A request is read within REQUEST_S seconds and at most MAX_BODY bytes, or the connection is closed.
"""

from __future__ import annotations

import io
import ipaddress
import socket
import sys
import time
import traceback
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib import resources
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlparse

from hexar.errors import USER_ERRORS
from hexar.web.live import LiveSource, RclpyWatcher
from hexar.web.store import Store

STATIC = {"index.html": "text/html; charset=utf-8", "app.js": "text/javascript; charset=utf-8",
          "style.css": "text/css; charset=utf-8"}
# The page's other ES modules (app.js imports them; a module script must come with a JavaScript type)
STATIC |= {f"{name}.js": STATIC["app.js"] for name in ("common", "runs", "run", "timeline", "path", "cards", "chat")}
MAX_BODY = 64 * 1024
REQUEST_S = 20.0  # to send one request, headers and body; an idle keep-alive connection is closed after it too
# The page's own script and style only: a recorded string that slipped into markup still could not run; and no
# other site may show the page in a frame (clickjacking the chat).
CSP = ("default-src 'self'; img-src 'self' data:; style-src 'self'; script-src 'self'; object-src 'none'; "
       "frame-ancestors 'none'; base-uri 'none'; form-action 'none'")
LOOPBACK_NAMES = frozenset({"localhost", "127.0.0.1", "::1"})


def static_file(name: str) -> bytes:
    return resources.files("hexar.web").joinpath("static", name).read_bytes()


def host_name(header: str) -> str:
    """The host of a Host header or an Origin's netloc, without the port: `[::1]:8080` -> `::1`."""
    h = header.strip().lower()
    if h.startswith("["):
        return h[1:h.find("]")] if "]" in h else h
    return h.rsplit(":", 1)[0] if h.count(":") == 1 else h


def is_ip(name: str) -> bool:
    try:
        ipaddress.ip_address(name)
    except ValueError:
        return False
    return True


def allowed_hosts(host: str) -> frozenset[str]:
    """The names a request may give in its Host header: loopback names, the address listened on and, when that
    is every interface, this machine's names. An IP address is always fine: DNS rebinding needs a name."""
    names = set(LOOPBACK_NAMES) | {host_name(host)}
    if host in {"0.0.0.0", "::", ""}:
        names |= {socket.gethostname().lower(), socket.getfqdn().lower()}
    return frozenset(names)


class _DeadlineReader(io.RawIOBase):
    """The socket read with one deadline for the whole request: a client that sends a byte every few seconds
    (slowloris) or announces a body it never sends is cut off at the deadline, not kept forever."""

    def __init__(self, sock: socket.socket, handler: Handler) -> None:
        self.sock, self.handler = sock, handler

    def readable(self) -> bool:
        return True

    def readinto(self, buf: Any) -> int:
        left = self.handler.deadline - time.monotonic()
        if left <= 0:
            raise TimeoutError("request not received in time")
        self.sock.settimeout(left)
        return self.sock.recv_into(buf)


class Handler(BaseHTTPRequestHandler):
    store: Store
    hosts: frozenset[str] = LOOPBACK_NAMES
    server_version = "hexar-web"
    deadline = 0.0

    def setup(self) -> None:
        super().setup()
        self.rfile = io.BufferedReader(_DeadlineReader(self.connection, self))

    def handle_one_request(self) -> None:
        self.deadline = time.monotonic() + REQUEST_S
        super().handle_one_request()

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
        self.send_header("X-Frame-Options", "DENY")
        self.send_header("Referrer-Policy", "no-referrer")
        self.send_header("Cross-Origin-Resource-Policy", "same-origin")
        self.end_headers()
        self.wfile.write(body)

    def _json(self, data: Any, status: int = 200) -> None:
        from hexar.safe_text import json_dumps  # strict JSON: a NaN from a recording becomes null, with a warning

        self._send(status, json_dumps(data, clean=True).encode(), "application/json")

    def _refuse(self, status: int, message: str) -> None:
        self.close_connection = True  # a body left unread must not be parsed as the next request
        self._json({"error": f"ERROR: {message}"}, status)

    def _foreign_host(self) -> bool:
        name = host_name(self.headers.get("Host") or "")
        if name in self.hosts or is_ip(name):
            return False
        self._refuse(HTTPStatus.MISDIRECTED_REQUEST, "this server answers only to its own address (Host header)")
        return True

    def _guard(self, fn: Any) -> None:
        """A user error becomes the CLI's one-line message; anything else a short line, never a traceback."""
        if self._foreign_host():
            return
        try:
            fn()
        except USER_ERRORS as e:
            self._json({"error": f"ERROR: {self.store.clean(str(e))}"}, HTTPStatus.BAD_REQUEST)
        except (BrokenPipeError, ConnectionResetError, TimeoutError):  # gone, or too slow to send its request
            self.close_connection = True
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

    def _cross_site(self) -> str | None:
        """Why a state-changing request does not come from the page itself, or None. A browser always sends
        Origin on a cross-origin POST, and only a script of the same origin can send application/json."""
        origin = self.headers.get("Origin")
        if origin is not None:
            url = urlparse(origin)
            if url.netloc.lower() != (self.headers.get("Host") or "").strip().lower():
                return "a question must come from this page, not from another site (Origin)"
        if self.headers.get("Sec-Fetch-Site", "same-origin") not in {"same-origin", "none"}:
            return "a question must come from this page, not from another site (Sec-Fetch-Site)"
        return None

    def _body_size(self) -> int | None:
        """The announced body size, or None after refusing a missing, negative, malformed or huge one."""
        raw = self.headers.get("Content-Length")
        if raw is None or not raw.strip().isdigit():
            self._refuse(HTTPStatus.LENGTH_REQUIRED if raw is None else HTTPStatus.BAD_REQUEST,
                         "a question needs a valid Content-Length")
            return None
        size = int(raw)
        if size > MAX_BODY:
            self._refuse(HTTPStatus.REQUEST_ENTITY_TOO_LARGE, f"request larger than {MAX_BODY} bytes")
            return None
        return size

    def do_POST(self) -> None:
        def body() -> None:
            from hexar.bounded_json import loads
            from hexar.errors import BadJsonError

            if urlparse(self.path).path != "/api/chat":
                self._refuse(HTTPStatus.NOT_FOUND, "no such endpoint")
                return
            why = self._cross_site()
            if why is not None:
                self._refuse(HTTPStatus.FORBIDDEN, why)
                return
            ctype = (self.headers.get("Content-Type") or "").split(";")[0].strip().lower()
            if ctype != "application/json":
                self._refuse(HTTPStatus.UNSUPPORTED_MEDIA_TYPE, "a question must be sent as application/json")
                return
            size = self._body_size()
            if size is None:
                return
            try:
                data = loads(self.rfile.read(size) or b"{}", max_chars=MAX_BODY)
            except BadJsonError:
                self._refuse(HTTPStatus.BAD_REQUEST, "the request is not JSON")
                return
            if not isinstance(data, dict):
                self._refuse(HTTPStatus.BAD_REQUEST, "the request must be a JSON object")
                return
            result = self.store.ask(str(data.get("name", "")), str(data.get("question", "")),
                                    _text_or_none(data.get("thread")), _text_or_none(data.get("task")))
            self._json(result)

        self._guard(body)

    def do_PUT(self) -> None:
        self._guard(lambda: self._refuse(HTTPStatus.METHOD_NOT_ALLOWED, "only GET and POST"))

    do_DELETE = do_PATCH = do_PUT


def _text_or_none(value: Any) -> str | None:
    return str(value)[:200] if value else None


def make_server(store: Store, host: str = "127.0.0.1", port: int = 8080) -> ThreadingHTTPServer:
    handler = type("HexarHandler", (Handler,), {"store": store, "hosts": allowed_hosts(host)})
    server = ThreadingHTTPServer((host, port), handler)
    server.daemon_threads = True
    return server


def live_source(live: bool, domain: int | None, launch_log: Path | None = None,
                transport: str = "auto") -> LiveSource | None:
    """`--live [--domain N] [--launch-log DIR] [--transport T]`: the robot's topics, read-only, and the newest
    launch's log of this computer. `auto` reads over DDS (the transport `hexar serve --transport dds` uses: the page
    then writes nothing at all and needs no ROS graph presence), or over rclpy where cyclonedds is missing."""
    from hexar.web.errors import WebError

    if not live:
        if domain is not None:
            raise WebError("--domain needs --live (it picks the robot's DDS domain)")
        if launch_log is not None:
            raise WebError("--launch-log needs --live (it follows the robot's launch beside its topics)")
        if transport != "auto":
            raise WebError("--transport needs --live (it picks how the page reads the robot)")
        return None
    from hexar.live.commands import domain_id, pick_transport

    chosen = pick_transport(transport, prefer="dds")
    return LiveSource.over_dds(domain_id(domain), launch_log=launch_log, transport=chosen)


def serve(root: Path | None, host: str, port: int, llm: str, checkpoints: Path | None, live: bool = False,
          domain: int | None = None, launch_log: Path | None = None, transport: str = "auto") -> int:
    from hexar.web.errors import WebError

    if root is None and not live:
        root = Path(".")
    source = live_source(live, domain, launch_log, transport)
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
        over = "rclpy" if isinstance(source.watcher, RclpyWatcher) else "DDS"
        what.append(f"the live robot on DDS domain {source.watcher.domain_id}, over {over}")
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
