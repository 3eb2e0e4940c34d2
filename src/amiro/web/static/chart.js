// A health chart on a canvas: one line per series (systolic and diastolic for blood pressure),
// the reference ranges shaded behind them, dated x axis, y axis with the unit.  What was drawn
// is returned (and kept in window.amiroChart) for the browser tests.

const SERIES_COLORS = ["#dc2626", "#2563eb"];

export function drawHealthChart(canvas, data, t, locale) {
  const dpr = window.devicePixelRatio || 1;
  const W = Math.max(240, canvas.parentElement.clientWidth), H = Math.round(Math.min(260, Math.max(180, W * 0.5)));
  canvas.style.width = `${W}px`; canvas.style.height = `${H}px`;
  canvas.width = Math.round(W * dpr); canvas.height = Math.round(H * dpr);  // resets the canvas
  const ctx = canvas.getContext("2d");
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  const additive = data.metric === "steps" || data.metric === "sleep";
  const keyOf = (name, i) => (name === "diastolic" ? "mean2" : additive ? "total" : "mean");
  const series = data.series.map((name, i) => ({
    name,
    color: SERIES_COLORS[i % SERIES_COLORS.length],
    points: data.days.map((d, k) => [k, d[keyOf(name, i)]]).filter((p) => p[1] !== null && p[1] !== undefined),
  }));
  const values = series.flatMap((s) => s.points.map((p) => p[1]));
  const ranges = Object.entries(data.ranges || {});
  for (const [, [lo, hi]] of ranges) values.push(lo, hi);
  const drawn = { metric: data.metric, unit: data.unit, series: [], xTicks: [], yTicks: [], ranges: 0 };
  window.amiroChart = drawn;
  if (!series.some((s) => s.points.length)) return drawn;

  const [lo, hi] = niceRange(Math.min(...values), Math.max(...values));
  const left = 52, right = 24, top = 26, bottom = 34;
  const n = Math.max(data.days.length - 1, 1);
  const X = (k) => left + k * (W - left - right) / n;
  const Y = (v) => top + (hi - v) / (hi - lo) * (H - top - bottom);

  // reference ranges, shaded in the series' colour
  ranges.forEach(([name, [a, b]]) => {
    const i = Math.max(0, data.series.indexOf(name));
    ctx.fillStyle = SERIES_COLORS[i % SERIES_COLORS.length] + "1f";
    ctx.fillRect(left, Y(b), W - left - right, Y(a) - Y(b));
    drawn.ranges += 1;
  });

  // axes and grid
  ctx.strokeStyle = "#d1d5db"; ctx.lineWidth = 1; ctx.fillStyle = "#374151";
  ctx.font = "11px system-ui, sans-serif";
  ctx.textAlign = "right"; ctx.textBaseline = "middle";
  for (const v of ticks(lo, hi, 5)) {
    ctx.beginPath(); ctx.moveTo(left, Y(v)); ctx.lineTo(W - right, Y(v)); ctx.stroke();
    const label = v >= 1000 ? `${(v / 1000).toLocaleString(locale)}k` : v.toLocaleString(locale);
    ctx.fillText(label, left - 6, Y(v));
    drawn.yTicks.push(v);
  }
  ctx.save(); ctx.textAlign = "left"; ctx.textBaseline = "top"; ctx.font = "600 11px system-ui, sans-serif";
  ctx.fillText(data.unit, 4, 4); ctx.restore();
  const fmt = new Intl.DateTimeFormat(locale, { day: "numeric", month: "short", timeZone: "UTC" });
  const every = Math.ceil(data.days.length / Math.max(2, Math.floor((W - left) / 64)));
  ctx.textAlign = "center"; ctx.textBaseline = "top";
  data.days.forEach((d, k) => {
    if ((data.days.length - 1 - k) % every) return;
    const label = fmt.format(new Date(`${d.day}T00:00:00Z`));
    ctx.beginPath(); ctx.moveTo(X(k), H - bottom); ctx.lineTo(X(k), H - bottom + 4); ctx.stroke();
    ctx.fillText(label, X(k), H - bottom + 6);
    drawn.xTicks.push({ day: d.day, label });
  });
  ctx.strokeStyle = "#6b7280"; ctx.beginPath(); ctx.moveTo(left, top); ctx.lineTo(left, H - bottom); ctx.lineTo(W - right, H - bottom); ctx.stroke();

  // the series, and a legend on top
  let lx = left + 40;
  for (const s of series) {
    ctx.strokeStyle = s.color; ctx.fillStyle = s.color; ctx.lineWidth = 2;
    ctx.beginPath();
    let prev = null;
    for (const [k, v] of s.points) {
      if (prev !== null && k === prev + 1) ctx.lineTo(X(k), Y(v)); else ctx.moveTo(X(k), Y(v));
      prev = k;
    }
    ctx.stroke();
    for (const [k, v] of s.points) { ctx.beginPath(); ctx.arc(X(k), Y(v), 2.5, 0, 2 * Math.PI); ctx.fill(); }
    const name = data.series.length > 1 ? t(s.name) : t(data.metric);
    ctx.fillRect(lx, 8, 14, 3); ctx.textAlign = "left"; ctx.textBaseline = "middle"; ctx.fillStyle = "#111827";
    ctx.fillText(name, lx + 18, 10);
    lx += ctx.measureText(name).width + 40;
    drawn.series.push({ name: s.name, points: s.points.length, color: s.color });
  }
  return drawn;
}

function niceRange(lo, hi) {
  if (lo === hi) { lo -= 1; hi += 1; }
  const pad = (hi - lo) * 0.08;
  const step = niceStep((hi - lo + 2 * pad) / 5);
  return [Math.floor((lo - pad) / step) * step, Math.ceil((hi + pad) / step) * step];
}

function niceStep(raw) {
  const p = 10 ** Math.floor(Math.log10(raw)), f = raw / p;
  return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * p;
}

function ticks(lo, hi, count) {
  const step = niceStep((hi - lo) / count), out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + 1e-9; v += step) out.push(Math.round(v * 1e6) / 1e6);
  return out;
}
