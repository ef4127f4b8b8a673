// The module panels of a run: asking a person for help step by step, what the robot said, the pizza choice.

import { el, clock } from "./common.js";

function valuesList(values) {
  return el("span", {}, values.map(([k, v]) => el("span", { class: `kv ${/distance|detect/i.test(k) ? "key" : ""}` }, el("b", {}, k), ` ${v}`)));
}

export function askHumanCard(run) {
  if (!run.ask_human.length) return null;
  return el("section", { class: "card", id: "ask-human" }, el("h2", {}, "Asking for help, step by step"),
    el("table", { class: "events" }, el("tbody", {}, run.ask_human.map((r) => el("tr", {},
      el("td", { class: "mono nowrap" }, clock(r.t_ns)), el("td", {}, r.message), el("td", {}, valuesList(r.values)))))));
}

export function ttsCard(run) {
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

export function pizzaCard(run) {
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
