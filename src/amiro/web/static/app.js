"use strict";
// The dashboard: plain JS, no build step.  State arrives over the websocket; actions are
// JSON POSTs that carry the session's CSRF token.

const TASK_DEFAULTS = {
  Say: { text: "Hello, I am here to help." },
  Display: { text: "Hello from the dashboard" },
  MoveTo: { target: "kitchen" },
  Wait: { seconds: 3 },
  Search: { person: "maria" },
  Listen: { expect: ["affirm"], timeout_s: 10 },
  RecognizeActivity: { person: "maria", activity: "drink_water", timeout_s: 30 },
  NotifyEnvironment: { status: "done", id: "dashboard" },
};

let csrf = null;
let home = null;
const $ = (id) => document.getElementById(id);

async function api(path, body) {
  const opts = body === undefined ? {} : {
    method: "POST",
    headers: { "Content-Type": "application/json", "X-CSRF-Token": csrf },
    body: JSON.stringify(body),
  };
  const res = await fetch("/api" + path, opts);
  if (res.status === 401) { window.location.href = "/login"; throw new Error("signed out"); }
  const data = await res.json();
  if (!res.ok) throw new Error(data.detail || res.statusText);
  return data;
}

function show(text) { $("action-result").textContent = text; }

// --- map ------------------------------------------------------------------------------------
function drawMap(state) {
  if (!home) return;
  const canvas = $("map"), ctx = canvas.getContext("2d");
  const [w, h] = home.size;
  const s = Math.min(canvas.width / w, canvas.height / h);
  const X = (x) => x * s, Y = (y) => canvas.height - y * s;
  const poly = (pts) => { ctx.beginPath(); pts.forEach(([x, y], i) => i ? ctx.lineTo(X(x), Y(y)) : ctx.moveTo(X(x), Y(y))); ctx.closePath(); };
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.font = "12px sans-serif";
  for (const [name, pts] of Object.entries(home.rooms)) {
    poly(pts); ctx.fillStyle = "#eef2ff"; ctx.fill(); ctx.strokeStyle = "#c7d2fe"; ctx.stroke();
    const cx = pts.reduce((a, p) => a + p[0], 0) / pts.length, cy = pts.reduce((a, p) => a + p[1], 0) / pts.length;
    ctx.fillStyle = "#6366f1"; ctx.fillText(name.replace("_", " "), X(cx) - 25, Y(cy));
  }
  ctx.fillStyle = "#d6d3d1";
  for (const f of home.furniture) { poly(f.polygon); ctx.fill(); }
  ctx.strokeStyle = "#374151"; ctx.lineWidth = 3;
  for (const [a, b] of home.walls) { ctx.beginPath(); ctx.moveTo(X(a[0]), Y(a[1])); ctx.lineTo(X(b[0]), Y(b[1])); ctx.stroke(); }
  ctx.lineWidth = 1;
  if (state.path && state.path.length) {
    ctx.strokeStyle = "#16a34a"; ctx.setLineDash([4, 3]); ctx.beginPath();
    state.path.forEach(([x, y], i) => i ? ctx.lineTo(X(x), Y(y)) : ctx.moveTo(X(x), Y(y)));
    ctx.stroke(); ctx.setLineDash([]);
  }
  for (const p of state.people || []) {
    ctx.fillStyle = "#f59e0b"; ctx.beginPath(); ctx.arc(X(p.x), Y(p.y), 7, 0, 2 * Math.PI); ctx.fill();
    ctx.fillStyle = "#92400e"; ctx.fillText(p.name, X(p.x) + 9, Y(p.y) - 6);
  }
  const r = state.robot;
  if (!r) return;  // a cloud dashboard before the first pose estimate
  ctx.fillStyle = "#2563eb"; ctx.beginPath(); ctx.arc(X(r.x), Y(r.y), 9, 0, 2 * Math.PI); ctx.fill();
  ctx.strokeStyle = "#fff"; ctx.beginPath(); ctx.moveTo(X(r.x), Y(r.y));
  ctx.lineTo(X(r.x + 0.4 * Math.cos(r.theta)), Y(r.y + 0.4 * Math.sin(r.theta))); ctx.stroke();
}

// --- state ----------------------------------------------------------------------------------
function render(state) {
  drawMap(state);
  $("clock").textContent = state.clock || "";
  const r = state.robot;
  $("robot-pose").textContent = r ? `x ${r.x.toFixed(2)} m, y ${r.y.toFixed(2)} m` : "unknown";
  const cur = state.current;
  $("current-task").textContent = cur ? `${cur.name} › ${cur.type} (${cur.task}), priority ${cur.priority}` : "nothing";
  $("queue").replaceChildren(...(state.queue || []).map((q) => li(`${q.name} › ${q.type} (priority ${q.priority})`)));
  $("transcript").replaceChildren(...(state.transcript || []).map((m) => li(`[${m.lang}] ${m.who}: ${m.text}`)));
  $("acks").replaceChildren(...(state.acks || []).slice().reverse().map((a) => li(`${a.id}: ${a.status} at ${a.ts}`)));
  renderRooms(state);
}

function li(text) { const e = document.createElement("li"); e.textContent = text; return e; }

function button(label, id, onClick) {
  const b = document.createElement("button");
  b.textContent = label; b.id = id; b.type = "button"; b.addEventListener("click", onClick);
  return b;
}

function renderRooms(state) {
  const rows = Object.keys(home ? home.rooms : {}).map((room) => {
    const tr = document.createElement("tr");
    const s = (state.sensors || {})[room] || {}, d = (state.devices || {})[room] || {};
    const cells = [room.replace("_", " "), `${s.temperature ?? "–"} °C`, `${s.humidity ?? "–"} %`, `${s.luminosity ?? "–"} lx`];
    for (const text of cells) { const td = document.createElement("td"); td.textContent = text; tr.append(td); }
    const td = document.createElement("td");
    const light = d.lights === "on" ? "off" : "on", blind = d.blinds === "open" ? "close" : "open";
    td.append(
      button(`lights ${light}`, `lights-${room}`, () => api("/devices", { room, device: "lights", state: light }).catch((e) => show(e.message))),
      button(`blinds ${blind}`, `blinds-${room}`, () => api("/devices", { room, device: "blinds", state: blind }).catch((e) => show(e.message))),
      button("heat to 31 °C", `heat-${room}`, () => api("/sensors", { room, sensor: "temperature", value: 31.5 }).catch((e) => show(e.message))),
    );
    tr.append(td);
    return tr;
  });
  $("rooms").replaceChildren(...rows);
}

function connect() {
  const ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws`);
  ws.onmessage = (ev) => render(JSON.parse(ev.data));
  ws.onclose = () => setTimeout(connect, 1000);
}

// --- health ---------------------------------------------------------------------------------
async function loadHealth() {
  const user = $("health-user").value, metric = $("health-metric").value;
  if (!user) { $("health-summary").textContent = "No health data yet."; return; }
  const data = await api(`/health/${user}/${metric}?days=14`);
  const canvas = $("health-chart"), ctx = canvas.getContext("2d");
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const key = metric === "steps" || metric === "sleep" ? "total" : "mean";
  const pts = data.days.map((d, i) => [i, d[key]]).filter((p) => p[1] !== null);
  if (pts.length) {
    const vals = pts.map((p) => p[1]), lo = Math.min(...vals), hi = Math.max(...vals), span = hi - lo || 1;
    const X = (i) => 30 + i * (canvas.width - 40) / Math.max(data.days.length - 1, 1);
    const Y = (v) => canvas.height - 20 - (v - lo) / span * (canvas.height - 40);
    ctx.strokeStyle = "#2563eb"; ctx.beginPath();
    pts.forEach(([i, v], k) => k ? ctx.lineTo(X(i), Y(v)) : ctx.moveTo(X(i), Y(v))); ctx.stroke();
    ctx.fillStyle = "#111"; ctx.fillText(hi.toFixed(1), 0, 20); ctx.fillText(lo.toFixed(1), 0, canvas.height - 20);
  }
  const latest = data.latest ? JSON.stringify(data.latest) : "none";
  $("health-summary").textContent = `Trend: ${data.direction}. Latest: ${latest}`;
}

// --- start ----------------------------------------------------------------------------------
async function main() {
  const me = await api("/me");
  csrf = me.csrf;
  $("who").textContent = me.user;
  home = await api("/map");
  const beh = await api("/behaviours");
  $("scenarios").replaceChildren(...beh.scenarios.map((name) => button(name, `scenario-${name}`, async () => {
    try { const r = await api("/scenarios", { name }); show(`Scenario ${name} started (${r.id})`); } catch (e) { show(e.message); }
  })));
  $("tasks").replaceChildren(...beh.task_types.map((type) => button(type, `task-${type}`, async () => {
    try { const r = await api("/tasks", { type, params: TASK_DEFAULTS[type] || {} }); show(`Task ${type} queued (${r.run})`); } catch (e) { show(e.message); }
  })));
  const health = await api("/health/users");
  $("health-user").replaceChildren(...health.users.map((u) => new Option(u, u)));
  $("health-metric").replaceChildren(...health.metrics.map((m) => new Option(m, m)));
  $("health-user").onchange = $("health-metric").onchange = loadHealth;
  loadHealth().catch((e) => show(e.message));
  const first = await api("/state");
  const residents = (first.people || []).map((person) => new Option(`as ${person.name}`, person.name));
  $("chat-user").replaceChildren(new Option("as me", ""), ...residents);
  render(first);
  connect();
}

$("chat-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  const text = $("chat-input").value, lang = $("chat-lang").value, user = $("chat-user").value;
  try {
    const r = await api("/chat", { text, lang, user });
    $("chat-reply").textContent = r.reply;
    $("chat-input").value = "";
  } catch (e) { $("chat-reply").textContent = e.message; }
});

$("logout").addEventListener("click", async () => {
  await fetch("/auth/logout", { method: "POST" });
  window.location.href = "/login";
});

main().catch((e) => show(e.message));
