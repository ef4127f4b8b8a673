// The chat panel: questions about the run to HEXAR's agent, in a thread kept in localStorage and on the server.

import { state, el, api, clock } from "./common.js";
import { highlight, causeChip } from "./timeline.js";

export function chatPanel(run) {
  const key = `hexar.thread.${run.recording}`;
  let thread = localStorage.getItem(key) || "";
  const log = el("div", { class: "messages", id: "chat-log" });
  const backend = el("span", { class: "badge none", id: "backend" }, "backend …");
  const threadInfo = el("p", { class: "muted small", id: "thread-info" });
  const input = el("input", { id: "chat-input", type: "text", placeholder: "Ask why…", autocomplete: "off", maxlength: "2000" });
  const send = el("button", { id: "chat-send", type: "submit" }, "Ask");
  const showThread = () => {
    threadInfo.textContent = !thread ? "new thread" : run.chat.recording_path === null ? `thread ${thread}`
      : `thread ${thread} · continue in a terminal: hexar chat ${run.chat.recording_path} --thread ${thread}`;
  };
  showThread();
  api("/api/backend").then((b) => { backend.textContent = `backend ${b.backend}`; }).catch((e) => { backend.textContent = e.message; });

  function bubble(who, ...kids) { const b = el("div", { class: `msg ${who}` }, kids); log.append(b); log.scrollTop = log.scrollHeight; return b; }
  function answerBubble(r) {
    if (r.no_task) return bubble("bot", el("p", { class: "answer" }, r.answer), el("p", { class: "meta" }, r.error));
    // small talk ("thanks") gets its reply, as the terminal chat and the robot give it
    if (r.error && r.intent === "smalltalk") return bubble("bot", el("p", { class: "answer" }, r.answer));
    if (r.error) return bubble("bot error", r.error);
    return bubble("bot", el("p", { class: "answer" }, r.answer),
      el("p", { class: "meta" }, `backend ${r.backend} · ${r.explainers.join(", ") || "follow-up"} · ${r.route}${r.fallback && r.fallback.length ? " · guard fell back" : ""}`),
      r.causes.length ? el("p", {}, r.causes.map(causeChip)) : null,
      r.evidence.length ? el("ul", { class: "evidence" }, r.evidence.map((ev) => el("li", {}, el("button", {
        class: "evlink", dataset: { key: ev.key }, title: "show on the timeline", on: { click: () => highlight(ev.key, ev) } },
        el("span", { class: "mono" }, clock(ev.t)), " ", el("span", { class: "muted" }, ev.topic), " ", ev.item)))) : null);
  }
  async function ask(q) {
    q = q.trim();
    if (!q) return;
    bubble("me", q);
    const wait = bubble("bot pending", "thinking…");
    send.disabled = true;
    try {
      const r = await api("/api/chat", { method: "POST", headers: { "Content-Type": "application/json" },
        body: JSON.stringify({ name: run.recording, question: q, thread, task: (state.run || run).task.task_id }) });
      wait.remove();
      if (r.thread) { thread = r.thread; localStorage.setItem(key, thread); showThread(); }
      answerBubble(r);
    } catch (e) { wait.remove(); bubble("bot error", e.message); }
    send.disabled = false;
    input.focus();
  }
  const form = el("form", { class: "ask", on: { submit: (e) => { e.preventDefault(); const q = input.value; input.value = ""; ask(q); } } }, input, send);
  const suggestions = el("div", { class: "suggest" }, ["What happened?", "why?", "What would have helped?", "What else happened?", "What errors were there?"].map((q) =>
    el("button", { class: "secondary", type: "button", on: { click: () => ask(q) } }, q)));
  const reset = el("button", { class: "link", type: "button", on: { click: () => { thread = ""; localStorage.removeItem(key); log.replaceChildren(); showThread(); } } }, "new thread");
  if (thread) {
    api(`/api/history?name=${encodeURIComponent(run.recording)}&thread=${encodeURIComponent(thread)}`)
      .then((h) => h.history.forEach((t) => { bubble("me", t.question); bubble("bot", el("p", { class: "answer" }, t.answer)); }))
      .catch(() => {});
  }
  return el("aside", { class: "card chat", id: "chat" }, el("div", { class: "row" }, el("h2", {}, "Ask the robot"), backend),
    threadInfo, log, suggestions, form, reset);
}
