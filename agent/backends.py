"""LLM backends behind one small interface: `embedded` (llama.cpp in-process), `ollama`, or `none`."""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from hexar.agent.errors import BackendError
from hexar.agent.model_files import model_path
from hexar.explainers.base import TextModel
from hexar.explainers.errors import ModelError

DEFAULT_OLLAMA_MODEL = "phi4"


def ollama_host() -> str:
    host = os.environ.get("OLLAMA_HOST", "http://127.0.0.1:11434")
    return host if host.startswith("http") else f"http://{host}"


class EmbeddedModel:
    """llama-cpp-python with the packaged Qwen2.5-Coder-1.5B-Instruct; greedy decoding, 2 threads."""

    def __init__(self, path: str | None = None, n_ctx: int = 2048, threads: int | None = None) -> None:
        import importlib.util

        if importlib.util.find_spec("llama_cpp") is None:
            raise BackendError("the embedded backend needs llama-cpp-python: run scripts/setup.sh")
        file = path or str(model_path())
        if not os.path.isfile(file):
            raise BackendError(f"embedded model not found at {file}: run scripts/setup.sh")
        self.name = "embedded:qwen2.5-coder-1.5b-instruct-q4_k_m"
        self.max_prompt_chars = 600
        self._file, self._n_ctx, self._threads = file, n_ctx, threads or min(4, os.cpu_count() or 2)
        self._loaded: Any = None
        self.load_s: float | None = None

    @property
    def _llm(self) -> Any:
        """The model, loaded on first use: an answer the failure check decides never waits for it."""
        if self._loaded is None:
            import time

            from hexar import progress

            began = time.perf_counter()
            with progress.step(f"loading the embedded model ({os.path.basename(self._file)}), once per process"):
                self._loaded = self._load()
            self.load_s = round(time.perf_counter() - began, 3)
        return self._loaded

    def _load(self) -> Any:
        from llama_cpp import Llama

        # llama.cpp reuses the evaluated prefix of the previous prompt, so a fixed system prompt costs once.
        # (LlamaRAMCache would keep more prefixes, but each saved state carries n_ctx x n_vocab logits: GBs.)
        return Llama(model_path=self._file, n_ctx=self._n_ctx, n_threads=self._threads, seed=0, verbose=False)

    def chat(self, messages: Sequence[Mapping[str, str]], *, schema: Mapping[str, Any] | None = None,
             max_tokens: int = 160) -> str:
        kwargs: dict[str, Any] = {"temperature": 0.0, "max_tokens": max_tokens}
        if schema is not None:
            kwargs["response_format"] = {"type": "json_object", "schema": dict(schema)}
        saved = None
        if messages and messages[0].get("role") == "system" and os.environ.get("HEXAR_PREFIX_CACHE", "1") != "0":
            from hexar.agent import prefix_cache

            name = prefix_cache.key(self._file, self._n_ctx, messages[0]["content"])
            saved = prefix_cache.cache_dir() / f"{name}.bin"
            prefix_cache.restore(self._llm, saved)
        try:
            # llama-cpp-python types messages as TypedDicts; ours are plain dicts of the same shape
            chat: Any = self._llm.create_chat_completion
            out: Any = chat(messages=[dict(m) for m in messages], **kwargs)
            text = str(out["choices"][0]["message"]["content"] or "")
        except Exception as err:  # llama.cpp raises bare RuntimeError/ValueError on context overflow
            raise ModelError(f"embedded model failed: {err}") from err
        if saved is not None:
            prefix_cache.save(self._llm, saved)
        return text


class OllamaModel:
    """An Ollama server through langchain-ollama's ChatOllama (temperature 0, like the paper)."""

    def __init__(self, model: str = DEFAULT_OLLAMA_MODEL, host: str | None = None, timeout: float = 60.0) -> None:
        from langchain_ollama import ChatOllama

        self.host = host or ollama_host()
        self.model = model
        self.name = f"ollama:{model}"
        self.max_prompt_chars = 8000
        self._chat = ChatOllama(model=model, base_url=self.host, temperature=0.0, client_kwargs={"timeout": timeout})

    def chat(self, messages: Sequence[Mapping[str, str]], *, schema: Mapping[str, Any] | None = None,
             max_tokens: int = 160) -> str:
        update: dict[str, Any] = {"num_predict": max_tokens}
        if schema is not None:
            update["format"] = dict(schema)
        llm = self._chat.model_copy(update=update)
        try:
            reply = llm.invoke([(m["role"], m["content"]) for m in messages])
        except Exception as err:  # httpx/ollama errors: unreachable server, unknown model
            raise ModelError(f"ollama at {self.host} failed: {err}") from err
        return str(reply.content)

    def choose_tool(self, messages: Sequence[Mapping[str, str]], tools: Sequence[Any]) -> str | None:
        """Native tool calling: the name of the first tool the model calls, or None."""
        try:
            reply = self._chat.bind_tools(list(tools)).invoke([(m["role"], m["content"]) for m in messages])
        except Exception as err:
            raise ModelError(f"ollama at {self.host} failed: {err}") from err
        calls = getattr(reply, "tool_calls", None) or []
        return str(calls[0]["name"]) if calls else None


def ollama_answers(host: str | None = None, timeout: float = 0.5) -> bool:
    import urllib.request  # with http and ssl, 50 ms of imports that `--llm none` never needs

    try:
        with urllib.request.urlopen(f"{host or ollama_host()}/api/tags", timeout=timeout) as r:
            json.loads(r.read() or b"{}")
            return bool(r.status == 200)
    except (OSError, ValueError):
        return False


def embedded_available() -> bool:
    import importlib.util

    return importlib.util.find_spec("llama_cpp") is not None and model_path().is_file()


@dataclass(frozen=True)
class Backend:
    """The model to use (None for `none`) and its name for reports."""

    name: str
    model: TextModel | None


def resolve(spec: str | None = None) -> Backend:
    """`auto` (default, or $HEXAR_LLM): Ollama if it answers, else embedded if installed, else none."""
    spec = (spec or os.environ.get("HEXAR_LLM") or "auto").strip()
    if spec == "none":
        return Backend("none", None)
    if spec == "auto":
        if ollama_answers():
            model = OllamaModel()
            return Backend(model.name, model)
        if embedded_available():
            return resolve("embedded")
        return Backend("none", None)
    if spec == "embedded":
        emb = EmbeddedModel()
        return Backend(emb.name, emb)
    if spec == "ollama" or spec.startswith("ollama:"):
        name = spec.partition(":")[2] or DEFAULT_OLLAMA_MODEL
        if not ollama_answers():
            raise BackendError(f"no Ollama server answers at {ollama_host()} (set OLLAMA_HOST or use --llm embedded)")
        oll = OllamaModel(name)
        return Backend(oll.name, oll)
    raise BackendError(f"unknown LLM backend {spec!r}: use auto, embedded, ollama[:model] or none")
