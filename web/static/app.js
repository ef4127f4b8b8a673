// HEXAR's page: `#/` shows the runs list, `#/run/NAME[/TASK][?thread=ID]` one run. The panels are ES modules
// beside this one (runs, run, timeline, path, cards, chat, common), served as they are.

import { showRun } from "./run.js";
import { showRuns } from "./runs.js";

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
