// The home map on a canvas: rooms, furniture, walls, doors (open or closed), the planned path,
// the lidar scan, people with their activity, the robot with its heading, and room labels
// drawn last so furniture never hides them.  Fitted to the canvas; the wheel or the buttons
// zoom, dragging pans.  What was drawn is kept in `scene` (canvas pixels), which the browser
// tests read.

export const COLORS = {
  room: "#eef2ff", roomEdge: "#c7d2fe", furniture: "#d6d3d1", wall: "#1f2937",
  doorOpen: "#16a34a", doorClosed: "#dc2626", path: "#2563eb", scan: "#a21caf",
  person: "#f59e0b", personText: "#78350f", robot: "#1d4ed8", label: "#312e81",
};

export class HomeMap {
  constructor(canvas, home, word) {
    this.canvas = canvas;
    this.home = home;
    this.word = word;  // rooms and activities in the page's language
    this.zoom = 1;
    this.pan = [0, 0];
    this.state = {};
    this.scan = [];
    this.scene = null;
    this.resize();
    new ResizeObserver(() => { this.resize(); this.draw(); }).observe(canvas.parentElement);
    canvas.addEventListener("wheel", (ev) => {
      ev.preventDefault();
      this.zoomAt(ev.deltaY < 0 ? 1.25 : 0.8, ev.offsetX, ev.offsetY);
    }, { passive: false });
    let drag = null;
    canvas.addEventListener("pointerdown", (ev) => { drag = [ev.clientX, ev.clientY]; canvas.setPointerCapture(ev.pointerId); });
    canvas.addEventListener("pointermove", (ev) => {
      if (!drag) return;
      this.pan = [this.pan[0] + ev.clientX - drag[0], this.pan[1] + ev.clientY - drag[1]];
      drag = [ev.clientX, ev.clientY];
      this.draw();
    });
    canvas.addEventListener("pointerup", () => { drag = null; });
  }

  resize() {
    // The canvas takes its card's width and the home's aspect ratio (no empty quarter).
    const [w, h] = this.home.size;
    const room = Math.max(200, this.canvas.parentElement.clientWidth);
    const height = Math.min(Math.round(room * h / w), Math.round(window.innerHeight * 0.72));
    const width = Math.min(room, Math.round(height * w / h) + 24);
    this.canvas.style.width = `${width}px`;
    this.canvas.style.height = `${height}px`;
    const dpr = window.devicePixelRatio || 1;  // the buffer matches the content box (no border)
    this.canvas.width = Math.round(this.canvas.clientWidth * dpr);
    this.canvas.height = Math.round(this.canvas.clientHeight * dpr);
    this.dpr = dpr;
  }

  fit() { this.zoom = 1; this.pan = [0, 0]; this.draw(); }

  zoomAt(factor, cx, cy) {
    const next = Math.min(8, Math.max(0.5, this.zoom * factor));
    const f = next / this.zoom;
    cx = cx ?? this.canvas.clientWidth / 2;
    cy = cy ?? this.canvas.clientHeight / 2;
    this.pan = [cx - (cx - this.pan[0]) * f, cy - (cy - this.pan[1]) * f];
    this.zoom = next;
    this.draw();
  }

  update(state) { this.state = state; this.draw(); }

  setScan(points) { this.scan = points; this.draw(); }

  draw() {
    const { canvas, home } = this;
    const ctx = canvas.getContext("2d");
    const W = canvas.clientWidth, H = canvas.clientHeight;
    const [w, h] = home.size, margin = 12;
    const s0 = Math.min((W - 2 * margin) / w, (H - 2 * margin) / h);
    const ox = (W - w * s0) / 2, oy = (H - h * s0) / 2, z = this.zoom, [px, py] = this.pan;
    const s = s0 * z;
    const X = (x) => px + z * (ox + x * s0), Y = (y) => py + z * (oy + (h - y) * s0);
    const scene = { scale: s, layers: [], doors: [], labels: [], people: [], robot: null, path: 0, scan: 0 };
    const layer = (name) => scene.layers.push(name);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
    const poly = (pts) => {
      ctx.beginPath();
      pts.forEach(([x, y], i) => (i ? ctx.lineTo(X(x), Y(y)) : ctx.moveTo(X(x), Y(y))));
      ctx.closePath();
    };
    const line = (a, b) => { ctx.beginPath(); ctx.moveTo(X(a[0]), Y(a[1])); ctx.lineTo(X(b[0]), Y(b[1])); ctx.stroke(); };

    layer("rooms");
    for (const pts of Object.values(home.rooms)) {
      poly(pts); ctx.fillStyle = COLORS.room; ctx.fill();
      ctx.strokeStyle = COLORS.roomEdge; ctx.lineWidth = 1; ctx.stroke();
    }
    layer("furniture");
    ctx.fillStyle = COLORS.furniture;
    for (const f of home.furniture) { poly(f.polygon); ctx.fill(); }
    layer("walls");
    ctx.strokeStyle = COLORS.wall; ctx.lineWidth = Math.max(2, 0.1 * s); ctx.lineCap = "square";
    for (const [a, b] of home.walls) line(a, b);

    layer("doors");
    const doors = this.state.doors || {};
    ctx.lineCap = "butt";
    for (const d of home.doors) {
      const open = doors[d.name] ?? d.open;
      ctx.strokeStyle = open ? COLORS.doorOpen : COLORS.doorClosed;
      ctx.lineWidth = open ? Math.max(3, 0.06 * s) : Math.max(5, 0.14 * s);
      ctx.setLineDash(open ? [6, 4] : []);
      line(d.a, d.b);
      ctx.setLineDash([]);
      scene.doors.push({ name: d.name, open, a: [X(d.a[0]), Y(d.a[1])], b: [X(d.b[0]), Y(d.b[1])] });
    }

    layer("path");
    const path = this.state.path || [];
    if (path.length > 1) {
      ctx.strokeStyle = COLORS.path; ctx.lineWidth = 2.5; ctx.setLineDash([7, 4]);
      ctx.beginPath();
      path.forEach(([x, y], i) => (i ? ctx.lineTo(X(x), Y(y)) : ctx.moveTo(X(x), Y(y))));
      ctx.stroke(); ctx.setLineDash([]);
      const [gx, gy] = path[path.length - 1];
      ctx.fillStyle = COLORS.path; ctx.beginPath(); ctx.arc(X(gx), Y(gy), 4, 0, 2 * Math.PI); ctx.fill();
      scene.path = path.length;
    }

    layer("scan");
    ctx.fillStyle = COLORS.scan;
    for (const [x, y] of this.scan) ctx.fillRect(X(x) - 1.5, Y(y) - 1.5, 3, 3);
    scene.scan = this.scan.length;

    layer("people");
    ctx.font = "600 12px system-ui, sans-serif";
    for (const p of this.state.people || []) {
      ctx.fillStyle = COLORS.person; ctx.beginPath(); ctx.arc(X(p.x), Y(p.y), Math.max(6, 0.22 * s), 0, 2 * Math.PI); ctx.fill();
      const label = p.activity && p.activity !== "idle" ? `${p.name} · ${this.word(p.activity)}` : p.name;
      this.pill(ctx, label, X(p.x) + 10, Y(p.y) - 12, COLORS.personText);
      scene.people.push({ name: p.name, activity: p.activity, x: X(p.x), y: Y(p.y), label });
    }

    layer("robot");
    const r = this.state.robot;
    if (r) {  // a cloud dashboard has no pose before the first estimate
      const rad = Math.max(8, 0.25 * s);
      ctx.fillStyle = COLORS.robot; ctx.beginPath(); ctx.arc(X(r.x), Y(r.y), rad, 0, 2 * Math.PI); ctx.fill();
      const hx = X(r.x) + Math.cos(r.theta) * rad * 1.8, hy = Y(r.y) - Math.sin(r.theta) * rad * 1.8;
      ctx.strokeStyle = COLORS.robot; ctx.lineWidth = 3; ctx.beginPath(); ctx.moveTo(X(r.x), Y(r.y)); ctx.lineTo(hx, hy); ctx.stroke();
      ctx.fillStyle = "#fff"; ctx.beginPath(); ctx.arc(X(r.x) + Math.cos(r.theta) * rad * 0.5, Y(r.y) - Math.sin(r.theta) * rad * 0.5, rad * 0.3, 0, 2 * Math.PI); ctx.fill();
      scene.robot = { x: X(r.x), y: Y(r.y), heading: [hx, hy] };
    }

    layer("labels");
    ctx.font = "600 13px system-ui, sans-serif";
    for (const [name, pts] of Object.entries(home.rooms)) {
      const [cx, cy] = centroid(pts);
      const text = this.word(name);
      const w = ctx.measureText(text).width;
      this.pill(ctx, text, X(cx) - w / 2, Y(cy), COLORS.label);
      scene.labels.push({ room: name, x: X(cx), y: Y(cy) });
    }
    this.scene = scene;
    window.amiroScene = scene;
  }

  pill(ctx, text, x, y, color) {
    const w = ctx.measureText(text).width;
    ctx.fillStyle = "rgba(255,255,255,0.85)";
    ctx.fillRect(x - 3, y - 12, w + 6, 16);
    ctx.fillStyle = color;
    ctx.fillText(text, x, y);
  }
}

function centroid(pts) {
  // The polygon's area centroid (the mean of its corners drifts towards detailed edges).
  let a = 0, cx = 0, cy = 0;
  for (let i = 0; i < pts.length; i++) {
    const [x0, y0] = pts[i], [x1, y1] = pts[(i + 1) % pts.length];
    const cross = x0 * y1 - x1 * y0;
    a += cross; cx += (x0 + x1) * cross; cy += (y0 + y1) * cross;
  }
  if (Math.abs(a) < 1e-9) return pts[0];
  return [cx / (3 * a), cy / (3 * a)];
}
