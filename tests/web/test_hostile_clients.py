"""The page's server against other web sites and hostile clients, with real HTTP to a real server on 127.0.0.1:
DNS rebinding (a foreign Host), cross-site posts (text/plain, forms, a foreign Origin), framing, bad
Content-Length, slow half-open requests, absolute paths in answers, symlinks out of the folder, long questions."""

from __future__ import annotations

import http.client
import json
import os
import shutil
import socket
import sqlite3
from pathlib import Path
from typing import Any
from urllib.parse import urlparse

import pytest

from hexar.agent.questions import MAX_QUESTION
from hexar.web import server as web_server
from tests.web.browser import served


def request(url: str, method: str, path: str, body: bytes | None = None,
            headers: dict[str, str] | None = None) -> tuple[int, dict[str, str], Any]:
    u = urlparse(url)
    conn = http.client.HTTPConnection(u.hostname or "", u.port, timeout=60)
    try:
        conn.request(method, path, body=body, headers=headers or {})
        r = conn.getresponse()
        raw = r.read()
        data = json.loads(raw) if r.getheader("Content-Type") == "application/json" else raw
        return r.status, {k.lower(): v for k, v in r.getheaders()}, data
    finally:
        conn.close()


def raw_exchange(url: str, data: bytes, read_for: float = 30.0) -> bytes:
    """Send `data` as is and read until the server closes (or `read_for` seconds pass without a byte)."""
    u = urlparse(url)
    with socket.create_connection((u.hostname or "", u.port or 0), timeout=read_for) as s:
        s.sendall(data)
        got = b""
        while True:
            try:
                chunk = s.recv(65536)
            except TimeoutError:
                return got + b"<still open>"
            if not chunk:
                return got
            got += chunk


def thread_count(checkpoints: Path) -> int:
    if not checkpoints.exists():
        return 0
    with sqlite3.connect(checkpoints) as db:
        if not db.execute("SELECT name FROM sqlite_master WHERE name = 'checkpoints'").fetchone():
            return 0
        return int(db.execute("SELECT COUNT(DISTINCT thread_id) FROM checkpoints").fetchone()[0])


CHAT = json.dumps({"name": "bagfile_5_1", "question": "Why did you fail?"}).encode()


def test_a_foreign_host_header_is_refused_so_dns_rebinding_reads_nothing(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        port = urlparse(url).port
        for path in ("/api/runs", "/api/run?name=bagfile_5_1", "/"):
            status, _, data = request(url, "GET", path, headers={"Host": f"attacker.example:{port}"})
            assert status == 421 and "Host" in data["error"]
            assert b"bagfile" not in json.dumps(data).encode()
        for host in (f"127.0.0.1:{port}", f"localhost:{port}", "localhost"):
            status, _, data = request(url, "GET", "/api/runs", headers={"Host": host})
            assert status == 200 and data["runs"]


@pytest.mark.parametrize(("headers", "status"), [
    ({"Content-Type": "text/plain"}, 415),
    ({"Content-Type": "application/x-www-form-urlencoded"}, 415),
    ({"Content-Type": "multipart/form-data; boundary=x"}, 415),
    ({"Content-Type": "application/json", "Origin": "http://attacker.example"}, 403),
    ({"Content-Type": "application/json", "Origin": "null"}, 403),
    ({"Content-Type": "application/json", "Sec-Fetch-Site": "cross-site"}, 403),
])
def test_a_post_from_another_site_plants_no_thread(webroot: Path, tmp_path: Path, headers: dict[str, str],
                                                   status: int) -> None:
    checkpoints = tmp_path / "t.sqlite"
    with served(webroot, checkpoints) as url:
        got, _, data = request(url, "POST", "/api/chat", CHAT, headers)
        assert got == status and data["error"].startswith("ERROR: ")
        # the page's own request, same origin, still works: the refusal was about the sender
        port = urlparse(url).port
        ok, _, answer = request(url, "POST", "/api/chat", CHAT, {"Content-Type": "application/json",
                                                                  "Origin": f"http://127.0.0.1:{port}"})
        assert ok == 200 and answer["answer"]
    assert thread_count(checkpoints) == 1


def test_the_page_cannot_be_framed(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        for path in ("/", "/api/runs"):
            _, headers, _ = request(url, "GET", path)
            assert "frame-ancestors 'none'" in headers["content-security-policy"]
            assert headers["x-frame-options"] == "DENY"


@pytest.mark.parametrize(("length", "status"), [("-1", 400), ("abc", 400), (str(10**12), 413), ("70000", 413)])
def test_a_bad_content_length_is_refused_without_reading_the_body(webroot: Path, tmp_path: Path, length: str,
                                                                  status: int) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        head = (f"POST /api/chat HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                f"Content-Length: {length}\r\n\r\n").encode()
        # the server answers and closes at once, though the client would go on sending (and never closes)
        reply = raw_exchange(url, head + b"x" * 1000)
        assert reply.startswith(f"HTTP/1.0 {status}".encode()) and not reply.endswith(b"<still open>")


def test_a_post_without_content_length_is_refused(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        head = b"POST /api/chat HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n\r\n"
        reply = raw_exchange(url, head)
        assert reply.startswith(b"HTTP/1.0 411") and not reply.endswith(b"<still open>")


@pytest.mark.parametrize("partial", [
    b"GET /api/runs HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ",  # headers never finished
    b"POST /api/chat HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 500\r\n\r\n{",
])
def test_a_slow_half_open_request_is_closed(webroot: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                            partial: bytes) -> None:
    monkeypatch.setattr(web_server, "REQUEST_S", 1.0)
    with served(webroot, tmp_path / "t.sqlite") as url:
        # the client sends part of a request and keeps the connection open: the server closes it, unanswered
        assert raw_exchange(url, partial, read_for=30.0) == b""


def test_no_answer_carries_an_absolute_path(webroot: Path, tmp_path: Path) -> None:
    with served(webroot, tmp_path / "t.sqlite") as url:
        bodies = [request(url, "GET", p)[2] for p in
                  ("/api/runs", "/api/run?name=bagfile_5_1", "/api/run?name=corrupt_run", "/api/run?name=nope")]
        bodies.append(request(url, "POST", "/api/chat", CHAT, {"Content-Type": "application/json"})[2])
    for body in bodies:
        text = json.dumps(body)
        assert str(webroot) not in text and str(tmp_path) not in text and str(Path.home()) + "/" not in text


def test_a_long_question_is_refused_without_echoing_it(webroot: Path, tmp_path: Path) -> None:
    question = "why " * (MAX_QUESTION // 2)
    with served(webroot, tmp_path / "t.sqlite") as url:
        _, _, data = request(url, "POST", "/api/chat", json.dumps({"name": "bagfile_5_1", "question": question})
                             .encode(), {"Content-Type": "application/json"})
    assert "too long" in data["answer"] and question[:200] not in json.dumps(data)


def test_symlinks_out_of_the_folder_are_refused(webroot: Path, tmp_path: Path) -> None:
    outside = tmp_path / "outside"
    shutil.copytree(webroot / "bagfile_5_1", outside / "secret_run")
    root = tmp_path / "root"
    root.mkdir()
    shutil.copytree(webroot / "bagfile_8_1", root / "real_run")
    os.symlink(outside / "secret_run", root / "linked_run")  # the whole recording links out
    for part in ("metadata.yaml", "db3"):  # a real folder whose metadata.yaml or .db3 links out
        run = root / f"{part}_run"
        shutil.copytree(webroot / "bagfile_8_1", run)
        target = run / "metadata.yaml" if part == "metadata.yaml" else next(run.glob("*.db3"))
        outside_file = outside / "secret_run" / ("metadata.yaml" if part == "metadata.yaml" else
                                                 next((outside / "secret_run").glob("*.db3")).name)
        target.unlink()
        os.symlink(outside_file, target)
    with served(root, tmp_path / "t.sqlite") as url:
        _, _, runs = request(url, "GET", "/api/runs")
        rows = {r["recording"]: r for r in runs["runs"]}
        assert rows["real_run"]["error"] == ""
        for name in ("linked_run", "metadata.yaml_run", "db3_run"):
            assert "outside the served folder" in rows[name]["error"] and rows[name]["latest"] is None
            status, _, data = request(url, "GET", f"/api/run?name={name}")
            assert status == 400 and "outside the served folder" in data["error"]
            status, _, data = request(url, "POST", "/api/chat", json.dumps({"name": name, "question": "Why?"})
                                      .encode(), {"Content-Type": "application/json"})
            assert status == 400 and "outside the served folder" in data["error"]


def test_many_posts_leave_the_conversation_file_bounded(webroot: Path, tmp_path: Path,
                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    from hexar.agent import threads

    monkeypatch.setattr(threads, "MAX_THREADS", 10)
    checkpoints = tmp_path / "t.sqlite"
    with served(webroot, checkpoints) as url:
        same = request(url, "POST", "/api/chat", CHAT, {"Content-Type": "application/json"})[2]["thread"]
        for i in range(60):  # new threads, and one thread continued, as a flood of posts would
            body = {"name": "bagfile_5_1", "question": "Why did you fail?", **({"thread": same} if i % 2 else {})}
            status, _, _ = request(url, "POST", "/api/chat", json.dumps(body).encode(),
                                   {"Content-Type": "application/json"})
            assert status == 200
    assert thread_count(checkpoints) <= 10
    with sqlite3.connect(checkpoints) as db:
        per_thread = db.execute("SELECT MAX(n) FROM (SELECT COUNT(*) AS n FROM checkpoints GROUP BY thread_id)")
        assert per_thread.fetchone()[0] == 1


def test_control_and_bidi_characters_never_reach_the_json_values(tmp_path: Path) -> None:
    from hexar.evals.scenarios.bag import BagBuilder, sec_ns

    root = tmp_path / "root"
    b = BagBuilder()
    t0 = sec_ns(1_741_600_000)
    step = {"skill": "navigate_to_zone", "params": {"zone": "kitchen\x1b[31m"}, "status": "failed",
            "error_msg": "Goal failed\x1b]52;c;ZWNobyBwd25lZA==\x07 \u202eevil"}
    b.task_info(t0, {"instruction": "Bring me \u202ethe coffee", "task_id": "t1", "task_status": "valid",
                     "task_error_msg": "", "skill_sequence": [step]})
    b.log(t0 + sec_ns(1), "bt_navigator", 40, "Goal failed\x1b[2J\u2066")
    b.write(root / "hostile")
    with served(root, tmp_path / "t.sqlite") as url:
        bodies = [request(url, "GET", p)[2] for p in ("/api/runs", "/api/run?name=hostile", "/api/lines?name=hostile")]
        bodies.append(request(url, "POST", "/api/chat", json.dumps({"name": "hostile", "question": "What happened?"})
                              .encode(), {"Content-Type": "application/json"})[2])

    def strings(value: Any) -> list[str]:
        if isinstance(value, dict):
            return [*value.keys(), *(s for v in value.values() for s in strings(v))]
        if isinstance(value, list):
            return [s for v in value for s in strings(v)]
        return [value] if isinstance(value, str) else []

    texts = [s for body in bodies for s in strings(body)]
    assert any("\\x1b" in s for s in texts)  # the hostile text is shown, made visible
    assert not any(ch in s for s in texts for ch in ("\x1b", "\x07", "\u202e", "\u2066"))
