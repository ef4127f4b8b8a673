"use strict";
// HEXAR's page. Rule: every string that came from a recording or an answer enters the DOM as text
// (text nodes / textContent / attribute values), never as markup. There is no innerHTML in this file.

const app = document.getElementById("app");
const state = { filters: { outcome: "", module: "", cause: "", text: "" }, poll: null, run: null, runsSeen: "",
  route: "", head: null, main: null, chat: null };
const LIVE_POLL_MS = 2000;  // a live run's page asks this often whether the robot's run changed

function el(tag, props, ...kids) {
  const n = document.createElement(tag);
  for (const [k, v] of Object.entries(props || {})) {
    if (v === null || v === undefined || v === false) continue;
    if (k === "class") n.className = v;
    else if (k === "on") for (const [ev, fn] of Object.entries(v)) n.addEventListener(ev, fn);
    else if (k === "dataset") Object.assign(n.dataset, v);
    else if (k === "style") for (const [sk, sv] of Object.entries(v)) n.style.setProperty(sk, sv);
    else n.setAttribute(k, v);
  }
  for (const kid of kids.flat(Infinity)) {
    if (kid === null || kid === undefined || kid === false) continue;
    n.append(kid instanceof Node ? kid : document.createTextNode(String(kid)));
  }
  return n;
}

async function api(path, opts) {
  let r;
  try { r = await fetch(path, opts); } catch (e) { throw new Error("ERROR: the HEXAR server does not answer"); }
  let data;
  try { data = await r.json(); } catch (e) { throw new Error(`ERROR: the server sent no answer (${r.status})`); }
  if (!r.ok) throw new Error(data.error || `ERROR: ${r.status}`);
  return data;
}

function errorLine(msg) { return el("p", { class: "error", role: "alert" }, String(msg)); }

function pad(n, w) { return String(n).padStart(w, "0"); }
function clock(tns) {
  const ms = Math.floor(tns / 1e6);
  const d = new Date(ms);
  return `${pad(d.getUTCHours(), 2)}:${pad(d.getUTCMinutes(), 2)}:${pad(d.getUTCSeconds(), 2)}.${pad(ms % 1000, 3)}`;
}
function secs(tns, t0) { return `+${((tns - t0) / 1e9).toFixed(1)} s`; }
function badge(outcome) { return el("span", { class: `badge ${(outcome || "none").replace(/ /g, "-")}` }, outcome || "no task"); }
// What a task's badge says: the robot's outcome, except a run that "succeeded" on a plan that did not match the
// request, shown as "wrong plan" (the server's verdict; older servers send only the outcome).
function verdict(t) { return t ? (t.verdict || t.outcome) : null; }
// A cause in words ("the plan used a skill the robot does not have"), its stable id on hover.
function causeWords(c, words) { return (words && words[c]) || c.replace(/^[^.]*\./, "").replace(/_/g, " "); }

// ---------------------------------------------------------------------------------------------- runs list
async function showRuns() {
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

// ---------------------------------------------------------------------------------------------- one run
function gantt(run) {
  const t0 = run.task.created_ns;
  const span = Math.max(run.task.last_update_ns - t0, 1e9);
  const pct = (t) => `${Math.min(100, Math.max(0, ((t - t0) / span) * 100)).toFixed(3)}%`;
  const rows = run.spans.map((s) => el("div", { class: "grow" },
    el("div", { class: "glabel", title: s.label }, `${s.index + 1}. ${s.skill}`),
    el("div", { class: "gtrack" }, s.status === "waiting" ? el("span", { class: "gwait", id: `skill-${s.index}`, dataset: { status: s.status, skill: s.skill } }, "waiting: never started") :
      el("div", { class: `gbar ${s.status}`, id: `skill-${s.index}`, dataset: { status: s.status, skill: s.skill },
        title: `${s.label}: ${s.status}${s.error_msg ? " — " + s.error_msg : ""}`,
        style: { left: pct(s.start_ns), width: `max(4px, calc(${pct(s.end_ns)} - ${pct(s.start_ns)}))` } },
        el("span", {}, `${s.status}${s.error_msg ? ": " + s.error_msg : ""}`)))));
  const ticks = el("div", { class: "gtrack ticks" }, run.events.map((ev) => el("button", {
    class: "tick", title: `${clock(ev.t_ns)} ${ev.topic}`, dataset: { key: ev.key }, style: { left: pct(ev.t_ns) },
    on: { click: () => highlight(ev.key) } })));
  const marker = el("div", { class: "gmarker", id: "gantt-marker", hidden: true });
  const axis = el("div", { class: "gaxis" }, [0, 0.25, 0.5, 0.75, 1].map((q) => el("span", { style: { left: `${q * 100}%` } },
    `${((span * q) / 1e9).toFixed(1)} s`)));
  return el("div", { class: "gantt", id: "gantt", dataset: { t0: String(t0), span: String(span) } }, rows,
    el("div", { class: "grow" }, el("div", { class: "glabel muted" }, "evidence"), ticks), el("div", { class: "grow" }, el("div", { class: "glabel" }), axis), marker);
}

function eventRow(ev, t0, extra) {
  return el("tr", { class: `ev ${extra || ""}`, dataset: { key: ev.key, t: String(ev.t_ns) } },
    el("td", { class: "mono nowrap" }, clock(ev.t_ns), el("br"), el("span", { class: "muted" }, secs(ev.t_ns, t0))),
    el("td", { class: "mono small" }, ev.topic),
    el("td", { class: "item" }, ev.item),
    el("td", {}, (ev.causes || []).map((c) => el("span", { class: "chip" }, c))));
}

function insertRow(ev, extra) {
  const body = document.getElementById("events-body");
  if (!body) return null;
  const existing = body.querySelector(`tr[data-key="${CSS.escape(ev.key)}"]`);
  if (existing) return existing;
  const row = eventRow(ev, state.run.task.created_ns, extra);
  const after = [...body.children].find((r) => Number(r.dataset.t) > ev.t_ns);
  body.insertBefore(row, after || null);
  return row;
}

function highlight(key, ev) {
  let row = document.querySelector(`#events-body tr[data-key="${CSS.escape(key)}"]`);
  if (!row && ev) row = insertRow({ key, t_ns: ev.t, topic: ev.topic, item: ev.item, causes: [ev.cause] }, "added");
  document.querySelectorAll("#events-body tr.hl, .tick.hl").forEach((n) => n.classList.remove("hl"));
  if (!row) return;
  row.classList.add("hl");
  document.querySelectorAll(`.tick[data-key="${CSS.escape(key)}"]`).forEach((n) => n.classList.add("hl"));
  const g = document.getElementById("gantt");
  const marker = document.getElementById("gantt-marker");
  if (g && marker) {
    const q = (Number(row.dataset.t) - Number(g.dataset.t0)) / Number(g.dataset.span);
    marker.style.setProperty("--q", String(Math.min(1, Math.max(0, q))));
    marker.hidden = false;
  }
  markPath(Number(row.dataset.t));
  row.scrollIntoView({ block: "center", behavior: "instant" });
}

function highlightCause(cause) {
  const rows = [...document.querySelectorAll("#events-body tr")].filter((r) => [...r.querySelectorAll(".chip")].some((c) => c.textContent === cause));
  document.querySelectorAll("#events-body tr.hl").forEach((n) => n.classList.remove("hl"));
  rows.forEach((r) => r.classList.add("hl"));
  if (rows.length) highlight(rows[0].dataset.key);
  rows.forEach((r) => r.classList.add("hl"));
}

function causeChip(c, words) {
  const meaning = words && words[c] ? `${words[c]} · ` : "";
  return el("button", { class: "chip cause", title: `${meaning}show its evidence on the timeline`, on: { click: () => highlightCause(c) } }, c);
}

function findingsCard(run) {
  return el("section", { class: "card", id: "findings" }, el("h2", {}, "What the explainers found"),
    el("p", { class: "muted small" }, "Each component explainer, asked \u201cWhat happened?\u201d about this task (no LLM)."),
    run.findings.map((f) => el("article", { class: `finding ${f.enough_information ? "" : "thin"}` },
      el("h3", {}, f.explainer, " ", el("span", { class: "muted small" }, `confidence ${f.confidence.toFixed(2)} · ${f.phrased_by}`)),
      el("p", { class: "answer" }, f.text),
      f.causes.length ? el("p", {}, f.causes.map((c) => causeChip(c, run.cause_words))) : null,
      f.causes.length && run.cause_words ? el("p", { class: "muted small meaning" }, f.causes.map((c) => causeWords(c, run.cause_words)).join("; ")) : null,
      f.counterfactual ? el("p", {}, el("b", {}, "Would have helped: "), f.counterfactual) : null,
      f.fix ? el("p", {}, el("b", {}, "Fix: "), f.fix) : null,
      f.details.length ? el("details", {}, el("summary", {}, `details (${f.details.length})`), el("ul", { class: "small" }, f.details.map((d) => el("li", { class: "pre" }, d)))) : null)),
    run.flags.length ? el("p", { class: "small" }, el("b", {}, "Flags: "), run.flags.map((fl) => el("span", { class: "flag" },
      `${fl.topic} = ${fl.at_start === null ? "unset" : fl.at_start} at start${fl.changes.length ? `, changed ${fl.changes.length}×` : ", unchanged"}`))) : null);
}

function timelineCard(run) {
  const t0 = run.task.created_ns;
  const body = el("tbody", { id: "events-body" }, run.events.map((ev) => eventRow(ev, t0)));
  const info = el("span", { class: "muted small", id: "lines-info" }, `${run.events.length} recorded items cited by the explainers`);
  const btn = el("button", { id: "all-lines", class: "secondary" }, "Show all filtered log lines");
  let shown = false;
  btn.addEventListener("click", async () => {
    if (shown) { body.querySelectorAll("tr.filtered").forEach((r) => r.remove()); btn.textContent = "Show all filtered log lines"; shown = false; info.textContent = `${run.events.length} recorded items cited by the explainers`; return; }
    btn.disabled = true;
    try {
      const lines = await api(`/api/lines?name=${encodeURIComponent(run.recording)}&task=${encodeURIComponent(run.task.task_id)}`);
      lines.lines.forEach((ln) => insertRow({ ...ln, causes: [] }, "filtered"));
      info.textContent = `${lines.kept} of ${lines.total} /rosout lines kept by the navigation filter${lines.shown < lines.kept ? ` (first ${lines.shown} shown)` : ""}; cited items highlighted`;
      btn.textContent = "Show only cited items"; shown = true;
    } catch (e) { info.replaceChildren(errorLine(e.message)); }
    btn.disabled = false;
  });
  return el("section", { class: "card", id: "timeline" }, el("h2", {}, "Timeline"), gantt(run),
    el("div", { class: "row" }, info, btn),
    el("div", { class: "scroll" }, el("table", { class: "events" }, el("thead", {}, el("tr", {}, ["time", "topic", "recorded", "cited for"].map((h) => el("th", {}, h)))), body)));
}

const SVG = "http://www.w3.org/2000/svg";
function svg(tag, attrs, ...kids) {
  const n = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs || {})) n.setAttribute(k, String(v));
  for (const kid of kids.flat()) if (kid) n.append(kid instanceof Node ? kid : document.createTextNode(String(kid)));
  return n;
}
function tip(text) { return svg("title", {}, text); }

// The path drawn by the page from thinned poses (the PNG figure of `--plot` is one click away): y points up.
function pathSvg(run) {
  const p = run.path;
  if (!p.points.length) return el("p", { class: "muted" }, "No /amcl_pose during this task.");
  const xs = p.points.map((q) => q[1]).concat(p.ellipses.flatMap((e) => [e[0] - e[2], e[0] + e[2]]));
  const ys = p.points.map((q) => q[2]).concat(p.ellipses.flatMap((e) => [e[1] - e[3], e[1] + e[3]]));
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const size = Math.max(x1 - x0, y1 - y0, 1) * 1.12;
  const cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  const X = (x) => ((x - cx) / size + 0.5) * 600, Y = (y) => (0.5 - (y - cy) / size) * 600;
  const unit = 600 / size;
  const root = svg("svg", { viewBox: "0 0 600 600", class: "pathsvg", id: "path-svg", role: "img",
    "aria-label": "the robot's path with its covariance, where each trip began and ended and where it stopped" });
  const grid = svg("g", { class: "grid" });
  const stepM = Math.pow(10, Math.floor(Math.log10(size / 2)));
  for (let g = Math.ceil((cx - size / 2) / stepM) * stepM; g < cx + size / 2; g += stepM) grid.append(svg("line", { x1: X(g), x2: X(g), y1: 0, y2: 600 }));
  for (let g = Math.ceil((cy - size / 2) / stepM) * stepM; g < cy + size / 2; g += stepM) grid.append(svg("line", { y1: Y(g), y2: Y(g), x1: 0, x2: 600 }));
  root.append(grid, svg("text", { x: 8, y: 592, class: "scale" }, `grid ${stepM} m`));
  root.append(svg("g", { class: "ellipses" }, p.ellipses.map((e) => svg("ellipse", { cx: X(e[0]), cy: Y(e[1]),
    rx: Math.max(e[2] * unit, 0.5), ry: Math.max(e[3] * unit, 0.5), class: e[4] ? "poor" : "ok" }))));
  root.append(svg("polyline", { class: "route", id: "path-line", points: p.points.map((q) => `${X(q[1]).toFixed(1)},${Y(q[2]).toFixed(1)}`).join(" ") }));
  p.trips.forEach((t) => {
    root.append(svg("circle", { class: "begin", cx: X(t.begin.x), cy: Y(t.begin.y), r: 7 }, tip(`trip ${t.index + 1} began (${t.skill})`)));
    root.append(svg("rect", { class: "end", x: X(t.end.x) - 6, y: Y(t.end.y) - 6, width: 12, height: 12 }, tip(`trip ${t.index + 1} ended (${t.skill}, ${t.status})`)));
  });
  if (p.stop) {
    const sx = X(p.stop.x), sy = Y(p.stop.y), failed = p.stop_label.startsWith("stopped");
    root.append(svg("path", { id: "path-stop", class: failed ? "stop failed" : "stop", d: `M${sx - 9},${sy - 9}L${sx + 9},${sy + 9}M${sx - 9},${sy + 9}L${sx + 9},${sy - 9}` }, tip(p.stop_label)));
  }
  root.append(svg("circle", { id: "path-marker", class: "marker", cx: -50, cy: -50, r: 9 }));
  root.dataset.scale = JSON.stringify([cx, cy, size]);
  return root;
}

function markPath(tns) {
  const m = document.getElementById("path-marker"), root = document.getElementById("path-svg");
  if (!m || !root || !state.run) return;
  const pts = state.run.path.points, rel = (tns - state.run.task.created_ns) / 1e9;
  let best = pts[0];
  for (const q of pts) { if (q[0] <= rel) best = q; else break; }
  const [cx, cy, size] = JSON.parse(root.dataset.scale);
  m.setAttribute("cx", String(((best[1] - cx) / size + 0.5) * 600));
  m.setAttribute("cy", String((0.5 - (best[2] - cy) / size) * 600));
  m.classList.add("shown");
}

function pathCard(run) {
  const p = run.path;
  const png = `/api/plot.png?name=${encodeURIComponent(run.recording)}&task=${encodeURIComponent(run.task.task_id)}`;
  return el("section", { class: "card", id: "path" }, el("div", { class: "row" }, el("h2", {}, "Path"),
      el("a", { href: png, target: "_blank", rel: "noopener", id: "png-link" }, "figure for a bug report (PNG)")),
    el("div", { class: "pathwrap" }, pathSvg(run),
      // the legend names only what the drawing holds: a run without trips shows no trip keys, and so on
      el("div", { class: "legend small", id: "path-legend" },
        p.points.length ? el("p", {}, el("span", { class: "key route" }), "path from /amcl_pose") : null,
        p.ellipses.length ? el("p", {}, el("span", { class: "key ell" }), "2σ covariance (red: above 0.2)") : null,
        p.trips.length ? el("p", {}, el("span", { class: "key begin" }), "trip began") : null,
        p.trips.length ? el("p", {}, el("span", { class: "key end" }), "trip ended") : null,
        p.stop ? el("p", {}, el("span", { class: "key stop" }), "where it stopped / ended") : null,
        p.points.length && run.events.length ? el("p", {}, el("span", { class: "key marker" }), "where it was at the evidence you pick") : null,
        el("p", { class: "muted" }, `${p.poses} poses from /amcl_pose${p.points.length < p.poses ? `, ${p.points.length} drawn` : ""}.`),
        p.trips.map((t) => el("p", { class: "flag" }, `trip ${t.index + 1} (${t.skill}, ${t.status}): (${t.begin.x.toFixed(2)}, ${t.begin.y.toFixed(2)}) → (${t.end.x.toFixed(2)}, ${t.end.y.toFixed(2)})`)),
        p.stop ? el("p", { class: `flag ${p.stop_label.startsWith("stopped") ? "stop" : "end"}` }, `${p.stop_label} at (${p.stop.x.toFixed(2)}, ${p.stop.y.toFixed(2)}), covariance ${p.stop.cov_xy.toFixed(3)}`) : null)));
}

function valuesList(values) {
  return el("span", {}, values.map(([k, v]) => el("span", { class: `kv ${/distance|detect/i.test(k) ? "key" : ""}` }, el("b", {}, k), ` ${v}`)));
}

function askHumanCard(run) {
  if (!run.ask_human.length) return null;
  return el("section", { class: "card", id: "ask-human" }, el("h2", {}, "Asking for help, step by step"),
    el("table", { class: "events" }, el("tbody", {}, run.ask_human.map((r) => el("tr", {},
      el("td", { class: "mono nowrap" }, clock(r.t_ns)), el("td", {}, r.message), el("td", {}, valuesList(r.values)))))));
}

function ttsCard(run) {
  if (!run.tts.length) return null;
  const started = run.tts.find((r) => r.message === "started");
  const end = [...run.tts].reverse().find((r) => r.message !== "started");
  const val = (r, k) => (r ? (r.values.find(([kk]) => kk === k) || [])[1] : undefined);
  const text = val(started, "text") || "";
  const said = val(end, "text_said");
  const utter = said !== undefined && text.startsWith(said)
    ? el("p", { class: "utterance" }, el("span", { class: "said" }, said), el("span", { class: "unsaid", title: "not said: cut off" }, text.slice(said.length)))
    : el("p", { class: "utterance" }, text);
  return el("section", { class: "card", id: "tts" }, el("h2", {}, "What I said"), utter,
    el("p", { class: "small" }, run.tts.map((r) => el("span", { class: "flag" }, `${clock(r.t_ns)} ${r.message}`, " ",
      valuesList(r.values.filter(([k]) => k !== "text" && k !== "text_said"))))));
}

function pizzaCard(run) {
  const p = run.pizza;
  if (!p) return null;
  const max = Math.max(1e-9, ...p.weights.map((w) => Math.abs(w.weight)));
  return el("section", { class: "card", id: "pizza" }, el("h2", {}, "Pizza recommendation"),
    el("p", {}, "Recommended: ", el("b", {}, p.recommended || "?"), ". ", p.text),
    el("p", { class: "muted small" }, "LIME weights toward the recommendation (decision tree over the recipes)"),
    el("div", { class: "weights" }, p.weights.slice(0, 12).map((w) => el("div", { class: "wrow" },
      el("span", { class: "wname" }, `${w.ingredient} (${w.present ? "have" : "don't have"})`),
      el("span", { class: "wtrack" }, el("span", { class: `wbar ${w.weight >= 0 ? "pos" : "neg"}`, style: { width: `${(Math.abs(w.weight) / max) * 100}%` } })),
      el("span", { class: "mono small" }, (w.weight >= 0 ? "+" : "") + w.weight.toFixed(3))))));
}

// ---------------------------------------------------------------------------------------------- chat
function chatPanel(run) {
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
  const suggestions = el("div", { class: "suggest" }, ["What happened?", "why?", "What would have helped?", "What else happened?"].map((q) =>
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

async function showRun(name, task) {
  clearTimeout(state.poll);
  state.route = location.hash;
  state.chat = null;
  app.replaceChildren(el("p", { class: "muted" }, "reading the recording…"));
  const started = performance.now();
  let run;
  try {
    run = await api(`/api/run?name=${encodeURIComponent(name)}${task ? `&task=${encodeURIComponent(task)}` : ""}`);
  } catch (e) {
    app.replaceChildren(el("p", {}, el("a", { href: "#/" }, "← runs")), errorLine(e.message));
    return;
  }
  renderRun(name, run);
  document.body.dataset.loadedMs = String(Math.round(performance.now() - started));
  if (run.live) state.poll = setTimeout(() => pollLive(name, task, run.version), LIVE_POLL_MS);
}

// A live run: ask whether it changed since the version shown; redraw only then, keeping the chat as it is.
async function pollLive(name, task, version) {
  const here = state.route;
  let run = null;
  try {
    run = await api(`/api/run?name=${encodeURIComponent(name)}${task ? `&task=${encodeURIComponent(task)}` : ""}&since=${encodeURIComponent(version)}`);
  } catch (e) { run = null; }  // the server is away for a moment: ask again later
  if (location.hash !== here || state.route !== here) return;  // the page moved on meanwhile
  if (run && !run.unchanged) renderRun(name, run);
  state.poll = setTimeout(() => pollLive(name, task, run ? run.version : version), LIVE_POLL_MS);
}

function runHead(name, run) {
  const tabs = el("nav", { class: "tabs" }, run.tasks.map((t) => el("a", {
    class: `tab ${run.task && t.task_id === run.task.task_id ? "active" : ""}`,
    href: `#/run/${encodeURIComponent(name)}/${encodeURIComponent(t.task_id)}` },
    `${t.order}. ${t.instruction || "(recovery)"} `, badge(verdict(t)))));
  const where = run.live ? `the robot, live · ${run.duration_s === undefined ? "nothing kept yet" : `${run.duration_s.toFixed(1)} s kept, from ${clock(run.start_ns)} UTC`}`
    : `${run.storage} · ${run.duration_s.toFixed(1)} s from ${clock(run.start_ns)} UTC`;
  return el("section", { class: "runhead" }, el("a", { href: "#/" }, "← runs"),
    el("h1", {}, run.recording, " ", run.live ? el("span", { class: "badge live" }, "live") : null, " ", run.task ? badge(verdict(run.task)) : null),
    el("p", { class: "muted" }, where),
    run.warnings.map((w) => el("p", { class: "warn" }, w)), tabs,
    run.task ? el("p", { class: "instruction" }, "\u201c", run.task.instruction || "(the robot's own recovery task)", "\u201d",
      run.task.valid ? null : el("span", { class: "error" }, ` invalid plan: ${run.task.error_msg}`),
      run.task.valid && verdict(run.task) === "wrong plan" ? el("span", { class: "error", id: "wrong-plan" },
        ` the robot reported "${run.task.outcome}", but its plan did not match the request (see the planner below)`) : null) : null);
}

function renderRun(name, run) {
  document.body.dataset.version = String(run.version === undefined ? "" : run.version);
  if (run.no_task) {  // a live robot with no task yet: the CLI's one line, and the page keeps following it
    state.run = null;
    state.chat = null;
    app.replaceChildren(runHead(name, run), el("p", { class: "muted", id: "no-task" }, run.no_task));
    document.body.dataset.ready = "none";
    return;
  }
  state.run = run;
  const head = runHead(name, run);
  const main = el("div", { class: "main" }, timelineCard(run), findingsCard(run), pathCard(run), askHumanCard(run), ttsCard(run), pizzaCard(run));
  if (state.chat && state.chat.isConnected && state.main && state.main.isConnected) {
    state.head.replaceWith(head);  // the chat is left in place: its messages, its input and its focus stay
    state.main.replaceWith(main);
  } else {
    state.chat = chatPanel(run);
    app.replaceChildren(head, el("div", { class: "grid" }, main, state.chat));
  }
  state.head = head;
  state.main = main;
  document.body.dataset.ready = run.task.task_id;
}

function route() {
  delete document.body.dataset.ready;
  const [path, query] = location.hash.split("?");
  const m = path.match(/^#\/run\/([^/]+)(?:\/([^/]+))?$/);
  if (!m) { showRuns(); return; }
  const name = decodeURIComponent(m[1]);
  // `#/run/NAME?thread=ID`: continue a conversation started elsewhere (`hexar chat ... --thread ID`, /thread)
  const thread = new URLSearchParams(query || "").get("thread");
  if (thread) {
    localStorage.setItem(`hexar.thread.${name}`, thread);
    history.replaceState(null, "", path);  // the thread is remembered; the address goes back to the run's
  }
  showRun(name, m[2] ? decodeURIComponent(m[2]) : null);
}
window.addEventListener("hashchange", route);
route();
