"""`hexar mcp` against hostile recordings, questions and networks: a /task_info of 2,000 nested brackets, a
metadata.yaml or .db3 that links out of the served folder, a 10 MB question, and HTTP off loopback, which needs
a token. Real recordings written with rosbags, a real server over stdio and over HTTP on this machine."""

from __future__ import annotations

import json
import os
import shutil
import socket
import subprocess
import time
import urllib.error
import urllib.request
from pathlib import Path

import httpx
import pytest
from mcp import ClientSession
from mcp.client.streamable_http import streamable_http_client

from hexar.agent.questions import MAX_QUESTION
from hexar.evals.scenarios.bag import _T, BagBuilder, sec_ns
from hexar.events import contract as c
from tests.tools.test_mcp_server import HEXAR, ROOT, _env, _free_port, call, error_of, run, stdio_session

T0 = sec_ns(1_741_600_000)
DEEP = "[" * 2000 + "]" * 2000
TOKEN = "s3cret-token-of-32-characters-xx"


def _recording(out: Path, extra_task_info: str | None = None) -> Path:
    b = BagBuilder()
    step = {"skill": "navigate_to_zone", "params": {"zone": "kitchen"}, "status": "failed", "error_msg": "Goal failed"}
    b.task_info(T0, {"instruction": "Bring me the coffee", "task_id": "t1", "task_status": "valid",
                     "task_error_msg": "", "skill_sequence": [step]})
    if extra_task_info is not None:
        b.raw(T0 + 1, c.TASK_INFO, c.STRING_TYPE, _T["std_msgs/msg/String"](data=extra_task_info))
    b.log(T0 + sec_ns(1), "bt_navigator", 40, "Goal failed")
    return b.write(out)


@pytest.fixture(scope="module")
def hostile(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("hostile")
    _recording(root / "deep", DEEP)
    nested_params = '{"task_id": "t2", "skill_sequence": [{"skill": "say", "params": ' + '{"a":' * 900 + "1" + \
        "}" * 900 + "}]}"
    _recording(root / "deep_params", nested_params)
    secret = _recording(tmp_path_factory.mktemp("outside") / "secret")
    for part in ("metadata.yaml", "db3"):
        run_dir = _recording(root / f"linked_{part.replace('.', '_')}")
        target = run_dir / "metadata.yaml" if part == "metadata.yaml" else next(run_dir.glob("*.db3"))
        source = secret / "metadata.yaml" if part == "metadata.yaml" else next(secret.glob("*.db3"))
        if part == "db3":  # the link keeps the name metadata.yaml lists
            os.rename(source, source.with_name(target.name))
            source = source.with_name(target.name)
        target.unlink()
        os.symlink(source, target)
    return root


def test_deeply_nested_task_info_is_skipped_not_a_recursion_error(hostile: Path) -> None:
    async def go() -> None:
        async with stdio_session(hostile) as s:
            listing = await call(s, "list_recordings")
            rows = {r["recording"]: r for r in listing["recordings"]}
            for name in ("deep", "deep_params"):
                assert rows[name]["tasks"][0]["instruction"] == "Bring me the coffee"
                task = await call(s, "inspect_task", recording=name)
                assert task["outcome"] == "failed"
                await call(s, "timeline", recording=name)
                answer = await call(s, "ask", recording=name, question="Why didn't you bring me the coffee?")
                assert answer["answer"]

    run(go)
    done = subprocess.run([HEXAR, "inspect", str(hostile / "deep")], capture_output=True, text=True, env=_env(),
                          timeout=120)
    assert done.returncode == 0 and "Traceback" not in done.stderr and "not task JSON" in done.stdout
    done = subprocess.run([HEXAR, "runs", str(hostile)], capture_output=True, text=True, env=_env(), timeout=120)
    assert done.returncode == 0 and "Traceback" not in done.stderr + done.stdout


def test_a_recording_whose_files_link_out_of_the_folder_is_refused(hostile: Path) -> None:
    async def go() -> None:
        async with stdio_session(hostile) as s:
            listing = await call(s, "list_recordings")
            rows = {r["recording"]: r for r in listing["recordings"]}
            for name in ("linked_metadata_yaml", "linked_db3"):
                assert "outside the served folder" in rows[name]["error"] and "tasks" not in rows[name]
                for tool in ("inspect_task", "timeline", "topic_contract"):
                    assert "outside the served folder" in await error_of(s, tool, recording=name)
                text = await error_of(s, "ask", recording=name, question="What happened?")
                assert "outside the served folder" in text

    run(go)


def test_a_10_mb_question_is_refused_at_once_without_echoing_it(hostile: Path) -> None:
    question = "why did you stop " * (10_000_000 // 17)

    async def go() -> None:
        async with stdio_session(hostile) as s:
            for tool in ("ask", "explain_navigation"):
                text = await error_of(s, tool, recording="deep", question=question)
                assert "too long" in text and str(MAX_QUESTION) in text and len(text) < 300
            assert (await call(s, "ask", recording="deep", question="What happened?"))["answer"]

    run(go)


def test_http_off_loopback_needs_a_token_and_says_so(hostile: Path) -> None:
    done = subprocess.run([HEXAR, "mcp", str(hostile), "--http", "--host", "0.0.0.0"], capture_output=True,
                          text=True, env={**_env(), "HEXAR_MCP_TOKEN": ""}, timeout=60)
    assert done.returncode == 2 and done.stderr.count("\n") == 1
    assert done.stderr.startswith("ERROR: --host 0.0.0.0") and "--token" in done.stderr
    done = subprocess.run([HEXAR, "mcp", str(hostile), "--http", "--host", "0.0.0.0", "--token", "short"],
                          capture_output=True, text=True, env=_env(), timeout=60)
    assert done.returncode == 2 and "at least 16 characters" in done.stderr


def _wait_port(proc: subprocess.Popen[bytes], port: int) -> None:
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        with socket.socket() as sock:
            if sock.connect_ex(("127.0.0.1", port)) == 0:
                return
        assert proc.poll() is None, proc.stderr.read() if proc.stderr else ""
        time.sleep(0.2)


def test_http_with_a_token_answers_only_requests_that_carry_it(hostile: Path) -> None:
    port = _free_port()
    proc = subprocess.Popen([HEXAR, "mcp", str(hostile), "--http", "--host", "0.0.0.0", "--port", str(port),
                             "--llm", "none", "--token", TOKEN], env=_env(), cwd=ROOT, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE)
    try:
        _wait_port(proc, port)
        url = f"http://127.0.0.1:{port}/mcp"
        for auth in (None, "Bearer wrong-token-wrong-token-xx", TOKEN):
            req = urllib.request.Request(url, b'{"jsonrpc": "2.0", "id": 1, "method": "tools/list"}',
                                         {"Content-Type": "application/json", **({"Authorization": auth} if auth
                                                                                 else {})})
            with pytest.raises(urllib.error.HTTPError) as refused:
                urllib.request.urlopen(req, timeout=30)
            assert refused.value.code == 401
            assert "Authorization: Bearer" in json.loads(refused.value.read())["error"]

        async def go() -> None:
            client = httpx.AsyncClient(headers={"Authorization": f"Bearer {TOKEN}"}, timeout=60)
            async with client, streamable_http_client(url, http_client=client) as (read, write, _), \
                    ClientSession(read, write) as s:
                await s.initialize()
                listing = await call(s, "list_recordings")
                assert {r["recording"] for r in listing["recordings"]} >= {"deep", "deep_params"}

        run(go)
    finally:
        proc.terminate()
        _, err = proc.communicate(timeout=10)
    assert b"clients must send Authorization: Bearer" in err and TOKEN.encode() not in err


def test_a_symlinked_recording_folder_is_not_listed_or_read(hostile: Path, tmp_path: Path) -> None:
    root = tmp_path / "root"
    shutil.copytree(hostile / "deep", root / "real")
    os.symlink(hostile / "deep", root / "linked")

    async def go() -> None:
        async with stdio_session(root) as s:
            listing = await call(s, "list_recordings")
            assert [r["recording"] for r in listing["recordings"]] == ["real"]
            assert "outside" in await error_of(s, "inspect_task", recording="linked")

    run(go)
