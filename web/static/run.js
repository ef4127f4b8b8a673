// One run's page: reads it, follows a live run without redrawing the chat, and lays out its panels.

import { askHumanCard, ttsCard, pizzaCard } from "./cards.js";
import { chatPanel } from "./chat.js";
import { app, state, LIVE_POLL_MS, el, api, errorLine, clock, badge, verdict } from "./common.js";
import { pathCard } from "./path.js";
import { findingsCard, timelineCard } from "./timeline.js";

export async function showRun(name, task) {
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
