"""The embedded model's evaluated system prompt, kept on disk between processes.

Routing with the embedded model sends the same system prompt (prompts/router.md plus the explainer list) before
every question; evaluating its ~260 tokens costs seconds on 2 CPU cores, at every cold start. llama.cpp can
save a context's state (the KV cache of the evaluated tokens) and load it again, after which only the tokens
that differ (the question) are evaluated. The file is keyed by everything that shapes that state: the model
file, the context size, the llama-cpp-python version and the system prompt. It is a cache: anything wrong with
it (missing, stale, unreadable, a different llama.cpp) means the prompt is evaluated as before.
"""

from __future__ import annotations

import ctypes
import hashlib
import json
import os
from pathlib import Path
from typing import Any

_MAGIC = b"HXPC1"


def cache_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "hexar" / "prefix"


def key(model_file: str, n_ctx: int, system: str) -> str:
    import llama_cpp

    stat = os.stat(model_file)
    parts = [os.path.basename(model_file), str(stat.st_size), str(n_ctx), llama_cpp.__version__, system]
    return hashlib.sha256("\0".join(parts).encode()).hexdigest()[:20]


def restore(llm: Any, path: Path) -> bool:
    """Load the saved state into a fresh context; True when it was loaded. A file that cannot be loaded is
    removed, so that the next reply writes a good one."""
    if llm.n_tokens != 0 or not path.is_file():
        return False
    if _load(llm, path):
        return True
    path.unlink(missing_ok=True)
    return False


def _load(llm: Any, path: Path) -> bool:
    import llama_cpp
    import numpy as np

    try:
        data = path.read_bytes()
        if not data.startswith(_MAGIC):
            return False
        head = len(_MAGIC) + 4
        meta_len = int.from_bytes(data[len(_MAGIC):head], "little")
        meta = json.loads(data[head:head + meta_len])
        n = int(meta["n_tokens"])
        ids_end = head + meta_len + 4 * n
        ids = np.frombuffer(data[head + meta_len:ids_end], dtype=np.intc)
        state = data[ids_end:]
        if len(ids) != n or len(state) != int(meta["state_bytes"]) or n > llm.n_ctx():
            return False
        buf = (ctypes.c_uint8 * len(state)).from_buffer_copy(state)
        if llama_cpp.llama_state_set_data(llm._ctx.ctx, buf, len(state)) != len(state):
            return False
    except (OSError, ValueError, KeyError, RuntimeError):
        return False
    llm.input_ids[:n] = ids
    llm.n_tokens = n
    return True


def save(llm: Any, path: Path) -> None:
    """Write the context's state (what was last evaluated: the system prompt and one question) once."""
    import llama_cpp
    import numpy as np

    if path.is_file() or llm.n_tokens == 0:
        return
    try:
        size = llama_cpp.llama_state_get_size(llm._ctx.ctx)
        buf = (ctypes.c_uint8 * int(size))()
        written = int(llama_cpp.llama_state_get_data(llm._ctx.ctx, buf, size))
        ids = np.asarray(llm.input_ids[:llm.n_tokens], dtype=np.intc).tobytes()
        meta = json.dumps({"n_tokens": int(llm.n_tokens), "state_bytes": written}).encode()
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_bytes(_MAGIC + len(meta).to_bytes(4, "little") + meta + ids + bytes(buf)[:written])
        tmp.replace(path)
    except (OSError, ValueError, RuntimeError):
        return
