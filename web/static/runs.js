// The runs list: every recording under the served folder with its latest task, filtered by outcome, module,
// cause or text; it redraws only when the list changed, and keeps polling while causes are found or a run is live.

import { app, state, LIVE_POLL_MS, el, api, errorLine, badge, verdict, causeWords } from "./common.js";

export async function showRuns() {
  clearInterval(state.poll);
  let data;
  try { data = await api("/api/runs"); } catch (e) { app.replaceChildren(errorLine(e.message)); return; }
  const live = data.runs.some((r) => r.live);
  const again = () => { state.poll = setTimeout(() => { if (location.hash === "" || location.hash === "#/") showRuns(); }, live ? LIVE_POLL_MS : 1500); };
  const seen = JSON.stringify(data);
  if (seen === state.runsSeen && document.getElementById("runs-table")) {  // unchanged: no redraw
    if (data.pending || live) again();
    return;
  }
  state.runsSeen = seen;
  document.getElementById("rootdir").textContent = data.root;
  const rows = data.runs;
  const modules = [...new Set(rows.flatMap((r) => r.modules))].sort();
  const causes = [...new Set(rows.flatMap((r) => r.causes || []))].sort();
  const f = state.filters;
  const select = (key, label, values) => el("label", {}, label, " ",
    el("select", { id: `filter-${key}`, on: { change: (e) => { f[key] = e.target.value; draw(); } } },
      el("option", { value: "" }, "all"), values.map((v) => el("option", { value: v, selected: f[key] === v, title: key === "cause" ? v : null },
        key === "cause" ? causeWords(v, data.cause_words) : v))));
  const search = el("input", { id: "filter-text", type: "search", placeholder: "search instruction or name",
    value: f.text, on: { input: (e) => { f.text = e.target.value; draw(); } } });
  const bar = el("div", { class: "filters" }, select("outcome", "outcome", ["failed", "wrong plan", "succeeded", "invalid", "running"]),
    select("module", "module", modules), select("cause", "cause", causes), search,
    data.pending ? el("span", { class: "muted" }, `finding causes… ${data.pending} runs left`) : null);
  const body = el("tbody");
  const table = el("table", { class: "runs", id: "runs-table" },
    el("thead", {}, el("tr", {}, ["recording", "tasks", "latest task", "outcome", "modules", "causes"].map((h) => el("th", {}, h)))), body);
  const count = el("p", { class: "muted" });
  function draw() {
    const text = f.text.toLowerCase();
    const shown = rows.filter((r) => (!f.outcome || (r.latest && verdict(r.latest) === f.outcome))
      && (!f.module || r.modules.includes(f.module)) && (!f.cause || (r.causes || []).includes(f.cause))
      && (!text || r.recording.toLowerCase().includes(text) || (r.latest && r.latest.instruction.toLowerCase().includes(text))));
    body.replaceChildren(...shown.map((r) => el("tr", { class: "run", dataset: { name: r.recording }, tabindex: "0",
      on: { click: () => { location.hash = `#/run/${encodeURIComponent(r.recording)}`; },
        keydown: (e) => { if (e.key === "Enter") location.hash = `#/run/${encodeURIComponent(r.recording)}`; } } },
      el("td", { class: "mono" }, r.recording, r.live ? el("span", { class: "badge live", title: "the robot, followed over DDS" }, "live") : null),
      el("td", {}, r.tasks),
      el("td", {}, r.error ? el("span", { class: "error" }, r.error) : (r.latest ? r.latest.instruction || "(recovery)" : (r.live ? "no task yet" : ""))),
      el("td", {}, r.error ? badge("unreadable") : badge(verdict(r.latest))),
      el("td", { class: "small" }, r.modules.join(", ")),
      el("td", { class: "small causes" }, r.causes === null ? el("span", { class: "muted" }, "…")
        : r.causes.map((c, i) => el("span", { class: "cause", title: c, dataset: { cause: c } }, i ? "; " : "", causeWords(c, data.cause_words)))))));
    count.textContent = `${shown.length} of ${rows.length} recordings`;
  }
  draw();
  const focused = document.activeElement && document.activeElement.id;  // a refresh keeps the search box focused
  app.replaceChildren(el("section", { class: "card" }, el("h1", {}, "Runs"), bar, count, table));
  if (focused && document.getElementById(focused)) document.getElementById(focused).focus();
  if (data.pending || live) again();
}
