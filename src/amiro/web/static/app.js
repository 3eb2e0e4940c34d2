// The dashboard: plain JS modules, no build step.  State arrives over the websocket; actions
// are JSON POSTs that carry the session's CSRF token.
import { drawHealthChart } from "./chart.js";
import { languageSelect, lang, SPEECH_LANG, t, translatePage, word } from "./i18n.js";
import { HomeMap } from "./map.js";

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
let map = null;
let last = {};
let residents = [];
let healthInfo = null;
let lastHealth = null;
let scenarios = {};
const seen = {};  // signatures of the lists last rendered, so unchanged ones are left alone
const $ = (id) => document.getElementById(id);
const pretty = (name) => String(name ?? "").replace(/_/g, " ");

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

let shown = null;  // the last message, as a key and values, so a new language re-renders it
function show(text, values) {
  shown = values === undefined ? null : [text, values];
  const named = values && values.name ? { ...values, name: word(values.name) } : values;
  $("action-result").textContent = values === undefined ? text : t(text, named);
}

function el(tag, text, attrs = {}) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  return e;
}

function changed(key, value) {
  const sig = JSON.stringify(value);
  if (seen[key] === sig) return false;
  seen[key] = sig;
  return true;
}

// --- behaviours -----------------------------------------------------------------------------
function renderBehaviours(state) {
  const cur = state.current;
  $("current-task").textContent = cur
    ? `${word(cur.name)} › ${word(cur.type)} (${cur.task}), ${t("priority")} ${cur.priority}, ${t("started_for", { s: Math.max(0, state.t - cur.started_s).toFixed(0) })}`
    : t("nothing");
  const steps = cur && cur.progress ? cur.progress : null;
  if (changed("progress", [steps, cur && cur.task, lang()])) {
    const items = steps ? [
      ...steps.done.map((s) => el("li", `${s.result === "success" ? "✔" : "✘"} ${word(s.type)}`, { class: `step ${s.result === "success" ? "done" : "failed"}`, "data-task": s.task })),
      el("li", `▶ ${word(cur.type)}`, { class: "step now", "data-task": cur.task }),
      ...steps.ahead.map((s) => el("li", word(s.type), { class: "step ahead", "data-task": s.task })),
    ] : [];
    $("progress").replaceChildren(...items);
  }
  const queue = state.queue || [];
  if (changed("queue", [queue, lang()])) {
    $("queue").replaceChildren(...(queue.length
      ? queue.map((q) => el("li", `${word(q.name)} › ${q.type ? word(q.type) : q.task} (${t("priority")} ${q.priority})`))
      : [el("li", t("queue_empty"), { class: "muted" })]));
  }
}

// --- timeline: what `amiro run`'s live log prints, in the page's language --------------------
const NARRATED = new Set(["notification", "graph_submitted", "graph_suspended", "graph_resumed", "task_started",
  "task_preempted", "graph_finished", "say", "heard", "person_found", "search_room", "activity_recognised", "ack",
  "fall_detected", "plan", "replan", "plan_failed", "plan_completed"]);

export function narrate(ev) {
  const v = { ...ev };
  if (ev.task_type) v.task_type = word(ev.task_type);
  if (ev.type === "task_finished") {
    return t(ev.result === "success" ? "ev_task_success" : "ev_task_failure", { ...v, result: word(ev.result) });
  }
  if (ev.type === "notification") { v.reason = ev.reason || ev.kind; v.user = ev.user || t("someone"); v.kind = word(ev.kind); }
  if (ev.type === "heard") v.speaker = ev.speaker || t("someone");
  if (ev.type === "activity_recognised") v.activity = word(ev.activity);
  if (ev.type === "ack") v.status = word(ev.status);
  if (ev.room) v.room = word(ev.room);
  if (ev.type === "plan") v.summary = ev.summary || (ev.steps || []).join(", ");
  if (ev.type === "graph_finished") v.outcome = word(ev.outcome);
  if (NARRATED.has(ev.type)) return t(`ev_${ev.type}`, v);
  const detail = Object.entries(ev).filter(([k, x]) => !["t", "type", "graph", "task"].includes(k) && x !== null && x !== "")
    .map(([k, x]) => `${k}: ${typeof x === "object" ? JSON.stringify(x) : x}`).join(", ");
  return `${pretty(ev.type)}${detail ? ` (${detail})` : ""}`;
}

function renderTimeline(state) {
  const events = state.events || [];
  if (!changed("timeline", [events.length, events.length && events[events.length - 1].t, lang()])) return;
  const box = $("timeline");
  const atEnd = box.scrollHeight - box.scrollTop - box.clientHeight < 40;
  const items = events.map((ev) => {
    const li = el("li", undefined, { class: `ev ev-${ev.type}`, "data-type": ev.type });
    if (ev.task) li.dataset.task = ev.task;
    if (ev.graph) li.dataset.graph = ev.graph;
    li.append(el("time", `${Number(ev.t).toFixed(1)} s`), el("span", narrate(ev)));
    return li;
  });
  box.replaceChildren(...(items.length ? items : [el("li", t("timeline_empty"), { class: "muted" })]));
  if (atEnd || !seen.timelineScrolled) { box.scrollTop = box.scrollHeight; seen.timelineScrolled = true; }
}

// --- conversation ---------------------------------------------------------------------------
function renderTranscript(state) {
  const lines = state.transcript || [];
  if (!changed("transcript", lines)) return;
  const box = $("transcript");
  box.replaceChildren(...lines.map((m) => {
    const li = el("li", undefined, { class: m.who === "robot" ? "robot" : "human" });
    li.append(el("b", `${m.who} `), el("span", m.text), el("small", ` ${m.lang}`));
    return li;
  }));
  box.scrollTop = box.scrollHeight;  // the newest message is always in view
}

function speak(text, language) {
  if (!$("speak").checked || !("speechSynthesis" in window)) return;
  const u = new SpeechSynthesisUtterance(text);
  u.lang = SPEECH_LANG[language] || language;
  window.speechSynthesis.cancel();
  window.speechSynthesis.speak(u);
}

// --- smart home -----------------------------------------------------------------------------
function toggle(id, onClick) {
  const b = el("button", undefined, { id, type: "button", role: "switch", "aria-checked": "false", class: "switch" });
  b.append(el("span", "", { class: "knob" }), el("span", "", { class: "switch-label" }));
  b.addEventListener("click", onClick);
  return b;
}

function buildRooms() {
  const cards = Object.keys(home.rooms).map((room) => {
    const card = el("div", undefined, { class: "room", "data-room": room });
    card.append(el("h3", word(room), { "data-room-name": room }), el("div", undefined, { class: "readings", id: `readings-${room}` }));
    const send = (device, state) => api("/devices", { room, device, state }).catch((e) => show(e.message));
    const lights = toggle(`lights-${room}`, () => send("lights", lights.getAttribute("aria-checked") === "true" ? "off" : "on"));
    const blinds = toggle(`blinds-${room}`, () => send("blinds", blinds.getAttribute("aria-checked") === "true" ? "close" : "open"));
    const heat = el("button", t("heat"), { id: `heat-${room}`, type: "button", class: "action", "data-i18n": "heat", "data-i18n-title": "heat_title" });
    heat.addEventListener("click", () => api("/sensors", { room, sensor: "temperature", value: 31.5 }).catch((e) => show(e.message)));
    card.append(el("div", undefined, { class: "toggles" }), heat);
    card.querySelector(".toggles").append(lights, blinds);
    return card;
  });
  $("rooms").replaceChildren(...cards);
}

function renderRooms(state) {
  for (const room of Object.keys(home.rooms)) {
    const s = (state.sensors || {})[room] || {}, d = (state.devices || {})[room] || {};
    const fmt = (v, unit) => (v === undefined ? "–" : `${Number(v).toLocaleString(lang(), { maximumFractionDigits: 1 })} ${unit}`);
    $(`readings-${room}`).replaceChildren(...[["temperature", s.temperature, "°C"], ["humidity", s.humidity, "%"], ["luminosity", s.luminosity, "lx"]]
      .map(([key, v, unit]) => { const r = el("span", undefined, { class: "reading" }); r.append(el("b", fmt(v, unit)), el("small", t(key))); return r; }));
    const on = d.lights === "on", open = d.blinds === "open";
    setSwitch($(`lights-${room}`), on, `${t("lights")}: ${t(on ? "on" : "off")}`, d.lights === undefined);
    setSwitch($(`blinds-${room}`), open, `${t("blinds")}: ${t(open ? "open" : "closed")}`, d.blinds === undefined);
  }
}

function setSwitch(button, checked, label, unknown) {
  button.setAttribute("aria-checked", String(checked));
  button.classList.toggle("unknown", unknown);
  button.querySelector(".switch-label").textContent = label;
}

// --- state ----------------------------------------------------------------------------------
function render(state) {
  last = state;
  map.update(state);
  $("clock").textContent = state.clock ? state.clock.replace("T", " ").slice(0, 19) : "";
  const r = state.robot;
  $("robot-pose").textContent = r ? `x ${r.x.toFixed(2)} m, y ${r.y.toFixed(2)} m, θ ${(r.theta * 180 / Math.PI).toFixed(0)}°` : t("unknown");
  renderBehaviours(state);
  renderTimeline(state);
  renderTranscript(state);
  renderRooms(state);
  const acks = (state.acks || []).slice().reverse();
  if (changed("acks", [acks, lang()])) {
    $("acks").replaceChildren(...(acks.length ? acks.map((a) => el("li", `${a.id}: ${word(a.status)} (${a.ts.replace("T", " ").slice(0, 19)})`))
      : [el("li", t("no_notifications"), { class: "muted" })]));
  }
  const stop = Boolean(state.estop);
  $("estop").setAttribute("aria-pressed", String(stop));
  $("estop").textContent = t(stop ? "estop_release" : "estop");
  $("estop").dataset.i18n = stop ? "estop_release" : "estop";
  $("estop-banner").hidden = !stop;
}

function connect() {
  const ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws`);
  ws.onmessage = (ev) => render(JSON.parse(ev.data));
  ws.onclose = () => setTimeout(connect, 1000);
}

// --- lidar ----------------------------------------------------------------------------------
let scanTimer = null;
async function pollScan() {
  try {
    const { points } = await api("/scan");
    if ($("lidar").checked) map.setScan(points);  // an answer arriving after "off" is dropped
  } catch (e) { show(e.message); }
}
$("lidar").addEventListener("change", () => {
  clearInterval(scanTimer);
  if ($("lidar").checked) { pollScan(); scanTimer = setInterval(pollScan, 500); } else map.setScan([]);
});

// --- health ---------------------------------------------------------------------------------
function fillMetrics() {
  const keep = $("health-metric").value;
  $("health-metric").replaceChildren(...healthInfo.metrics.map((m) => new Option(t(m), m)));
  if (keep) $("health-metric").value = keep;
}

async function loadHealth() {
  const user = $("health-user").value, metric = $("health-metric").value;
  const summary = $("health-summary");
  if (!user) { summary.replaceChildren(el("dd", t("no_health"))); drawHealthChart($("health-chart"), { metric, series: [], days: [] }, t, lang()); return; }
  const raw = await api(`/health/${user}/${metric}?days=14`);
  const data = { ...raw, unit: word(raw.unit) };  // "steps" is a word to translate
  $("demo-badge").hidden = !data.demo;
  lastHealth = data;
  drawHealthChart($("health-chart"), data, t, lang());
  const num = (v) => Number(v).toLocaleString(lang(), { maximumFractionDigits: 1 });
  const when = (ts) => new Intl.DateTimeFormat(lang(), { dateStyle: "medium", timeStyle: "short", timeZone: "UTC" }).format(new Date(ts));
  const l = data.latest;
  const latest = !l ? t("no_latest")
    : metric === "blood_pressure" ? `${num(l.systolic)}/${num(l.diastolic)} ${data.unit} (${t("systolic")}/${t("diastolic")}) · ${when(l.ts)}`
      : `${num(l.value)} ${data.unit} · ${when(l.ts)}`;
  const direction = data.direction === "unknown" ? t("unknown_trend") : t(data.direction);
  const slope = data.direction === "unknown" ? "" : ` (${data.slope_per_day >= 0 ? "+" : ""}${num(data.slope_per_day)} ${data.unit} ${t("per_day")})`;
  const ref = data.series.map((s) => data.ranges[s]).filter(Boolean).map(([a, b]) => `${num(a)}–${num(b)}`).join(" / ");
  summary.replaceChildren(
    el("dt", t("latest")), el("dd", latest, { id: "health-latest" }),
    el("dt", t("trend")), el("dd", `${direction}${slope}`),
    el("dt", t("reference")), el("dd", `${ref} ${data.unit}`),
  );
}

// --- header actions -------------------------------------------------------------------------
$("estop").addEventListener("click", async () => {
  const engaged = $("estop").getAttribute("aria-pressed") !== "true";
  try { await api("/estop", { engaged }); $("estop").setAttribute("aria-pressed", String(engaged)); } catch (e) { show(e.message); }
});

$("fall").addEventListener("click", async () => {
  try {
    const r = await api("/scenarios", { name: "fall", user: residents[0] || "" });
    show("scenario_started", { name: "fall", id: r.id, priority: r.priority });
  } catch (e) { show(e.message); }
});

$("chat-form").addEventListener("submit", async (ev) => {
  ev.preventDefault();
  const text = $("chat-input").value, language = $("chat-lang").value, user = $("chat-user").value;
  try {
    const r = await api("/chat", { text, lang: language, user });
    $("chat-reply").textContent = r.reply;
    $("chat-input").value = "";
    speak(r.reply, r.lang);
  } catch (e) { $("chat-reply").textContent = e.message; }
});

$("logout").addEventListener("click", async () => {
  await fetch("/auth/logout", { method: "POST" });
  window.location.href = "/login";
});

$("zoom-in").addEventListener("click", () => map.zoomAt(1.25));
$("zoom-out").addEventListener("click", () => map.zoomAt(0.8));
$("zoom-fit").addEventListener("click", () => map.fit());

function fillChatUsers() {
  const keep = $("chat-user").value;
  $("chat-user").replaceChildren(new Option(t("as_me"), ""), ...residents.map((n) => new Option(t("as_person", { name: n }), n)));
  $("chat-user").value = keep;
}

function onLanguage(next) {
  $("chat-lang").value = next;
  for (const k of Object.keys(seen)) delete seen[k];
  fillChatUsers();
  if (shown) show(...shown);
  for (const h of document.querySelectorAll("[data-room-name]")) h.textContent = word(h.dataset.roomName);
  for (const b of document.querySelectorAll("[data-task-type]")) b.textContent = word(b.dataset.taskType);
  for (const b of document.querySelectorAll("[data-scenario]")) b.textContent = `${word(b.dataset.scenario)} · ${scenarios[b.dataset.scenario]}`;
  if (healthInfo) fillMetrics();
  if (map) { render(last); loadHealth().catch((e) => show(e.message)); }
}

// --- start ----------------------------------------------------------------------------------
async function main() {
  languageSelect($("ui-lang"), onLanguage);
  translatePage();
  $("chat-lang").value = lang();
  const me = await api("/me");
  csrf = me.csrf;
  $("who").textContent = me.user;
  home = await api("/map");
  map = new HomeMap($("map"), home, word);
  const beh = await api("/behaviours");
  scenarios = beh.scenarios;
  $("scenarios").replaceChildren(...Object.entries(beh.scenarios).map(([name, priority]) => {
    const b = el("button", `${word(name)} · ${priority}`, { id: `scenario-${name}`, type: "button", "data-scenario": name });
    b.addEventListener("click", async () => {
      try { const r = await api("/scenarios", { name, user: residents[0] || "" }); show("scenario_started", { name, id: r.id, priority: r.priority }); } catch (e) { show(e.message); }
    });
    return b;
  }));
  $("tasks").replaceChildren(...beh.task_types.map((type) => {
    const b = el("button", word(type), { id: `task-${type}`, type: "button", "data-task-type": type });
    b.addEventListener("click", async () => {
      try { const r = await api("/tasks", { type, params: TASK_DEFAULTS[type] || {} }); show("task_queued", { type: word(type), run: r.run }); } catch (e) { show(e.message); }
    });
    return b;
  }));
  buildRooms();
  healthInfo = await api("/health/users");
  $("health-user").replaceChildren(...healthInfo.users.map((u) => new Option(u, u)));
  fillMetrics();
  $("health-user").onchange = $("health-metric").onchange = () => loadHealth().catch((e) => show(e.message));
  window.addEventListener("resize", () => lastHealth && drawHealthChart($("health-chart"), lastHealth, t, lang()));
  const first = await api("/state");
  residents = (first.people || []).map((p) => p.name);
  fillChatUsers();
  render(first);
  await loadHealth().catch((e) => show(e.message));
  connect();
  document.body.dataset.ready = "true";
}

main().catch((e) => show(e.message));
