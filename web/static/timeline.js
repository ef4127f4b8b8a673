// One run's timeline: the task's steps as a Gantt chart, the recorded items the explainers cite, and their
// findings. Choosing a piece of evidence highlights it here and marks where the robot was on the path.

import { state, el, api, errorLine, clock, secs, causeWords } from "./common.js";
import { markPath } from "./path.js";

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

export function highlight(key, ev) {
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

export function causeChip(c, words) {
  const meaning = words && words[c] ? `${words[c]} · ` : "";
  return el("button", { class: "chip cause", title: `${meaning}show its evidence on the timeline`, on: { click: () => highlightCause(c) } }, c);
}

export function findingsCard(run) {
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

export function timelineCard(run) {
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
      info.textContent = `${lines.kept} of ${lines.total} log lines (/rosout, launch.log) kept by the navigation filter${lines.shown < lines.kept ? ` (first ${lines.shown} shown)` : ""}; cited items highlighted`;
      btn.textContent = "Show only cited items"; shown = true;
    } catch (e) { info.replaceChildren(errorLine(e.message)); }
    btn.disabled = false;
  });
  return el("section", { class: "card", id: "timeline" }, el("h2", {}, "Timeline"), gantt(run),
    el("div", { class: "row" }, info, btn),
    el("div", { class: "scroll" }, el("table", { class: "events" }, el("thead", {}, el("tr", {}, ["time", "topic", "recorded", "cited for"].map((h) => el("th", {}, h)))), body)));
}
