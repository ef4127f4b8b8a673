// Shared by every panel of HEXAR's page: its state, DOM and API helpers, times and outcome words.
// Rule: every string that came from a recording or an answer enters the DOM as text (text nodes / textContent /
// attribute values), never as markup. There is no innerHTML in any of the page's modules.

export const app = document.getElementById("app");

export const state = { filters: { outcome: "", module: "", cause: "", text: "" }, poll: null, run: null, runsSeen: "",
  route: "", head: null, main: null, chat: null };

export const LIVE_POLL_MS = 2000;  // a live run's page asks this often whether the robot's run changed

export function el(tag, props, ...kids) {
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

export async function api(path, opts) {
  let r;
  try { r = await fetch(path, opts); } catch (e) { throw new Error("ERROR: the HEXAR server does not answer"); }
  let data;
  try { data = await r.json(); } catch (e) { throw new Error(`ERROR: the server sent no answer (${r.status})`); }
  if (!r.ok) throw new Error(data.error || `ERROR: ${r.status}`);
  return data;
}

export function errorLine(msg) { return el("p", { class: "error", role: "alert" }, String(msg)); }

function pad(n, w) { return String(n).padStart(w, "0"); }

export function clock(tns) {
  const ms = Math.floor(tns / 1e6);
  const d = new Date(ms);
  return `${pad(d.getUTCHours(), 2)}:${pad(d.getUTCMinutes(), 2)}:${pad(d.getUTCSeconds(), 2)}.${pad(ms % 1000, 3)}`;
}

export function secs(tns, t0) { return `+${((tns - t0) / 1e9).toFixed(1)} s`; }

export function badge(outcome) { return el("span", { class: `badge ${(outcome || "none").replace(/ /g, "-")}` }, outcome || "no task"); }
// What a task's badge says: the robot's outcome, except a run that "succeeded" on a plan that did not match the
// request, shown as "wrong plan" (the server's verdict; older servers send only the outcome).

export function verdict(t) { return t ? (t.verdict || t.outcome) : null; }
// A cause in words ("the plan used a skill the robot does not have"), its stable id on hover.

export function causeWords(c, words) { return (words && words[c]) || c.replace(/^[^.]*\./, "").replace(/_/g, " "); }
