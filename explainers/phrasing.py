"""Optional LLM phrasing of a grounded finding; the template text stays the fallback."""

from __future__ import annotations

from hexar.explainers.base import Explanation, TextModel
from hexar.explainers.errors import ModelError
from hexar.prompts import load


def phrase(model: TextModel | None, prompt_name: str, question: str, facts: str, grounded: Explanation) -> Explanation:
    """Ask `model` to say `grounded` in its own words, from `facts` only; keep the template on any failure."""
    if model is None:
        return grounded
    # A small local model reads ~30 tokens/s on a laptop CPU: keep its facts short, newest last.
    limit = int(getattr(model, "max_prompt_chars", 8000))
    if len(facts) > limit:
        facts = grounded.text + "\n" + facts[-(limit - len(grounded.text) - 1):]
    messages = [
        {"role": "system", "content": load(prompt_name)},
        {"role": "user", "content": f"Facts:\n{facts}\n\nQuestion: {question}\nAnswer:"},
    ]
    try:
        text = model.chat(messages, max_tokens=90).strip()
    except ModelError:
        return grounded
    if not text:
        return grounded
    return grounded.model_copy(update={"text": text, "phrased_by": model.name})
