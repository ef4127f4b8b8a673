// The path panel: the robot's path drawn from thinned poses (y points up), with covariance, trips and where it
// stopped; the PNG figure of `--plot` is one click away.

import { state, el } from "./common.js";

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

export function markPath(tns) {
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

export function pathCard(run) {
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
