// The scope: the last 10 s of the chosen telemetry channels, pause, two cursors.
'use strict';

const HISTORY_S = 10;          // the scope keeps and shows this much
const RATE_WINDOW_MS = 1000;   // the update counter counts over this window

const scope = (() => {
  let channels = [];                            // [{name, unit}] from /api/info
  const selected = new Set(['pos_x_mm', 'pos_y_mm', 'following_x_um']);
  const series = {};                            // name -> [{x, y}], the last HISTORY_S
  let chart = null;
  let dirty = false;
  const cursors = { a: null, b: null, next: 'a' };
  const drawTimes = [];

  const colors = ['#1f6feb', '#d1242f', '#1a7f37', '#9a6700', '#8250df', '#bf3989',
                  '#0a7ea4', '#6e7781', '#953800', '#116329', '#cf222e', '#0550ae'];

  const cursorPlugin = {
    id: 'tnvCursors',
    afterDraw(c) {
      const { ctx, chartArea, scales } = c;
      for (const [key, color] of [['a', '#d1242f'], ['b', '#1f6feb']]) {
        const t = cursors[key];
        if (t === null || t < scales.x.min || t > scales.x.max) continue;
        const x = scales.x.getPixelForValue(t);
        ctx.save();
        ctx.strokeStyle = color;
        ctx.setLineDash([5, 4]);
        ctx.beginPath();
        ctx.moveTo(x, chartArea.top);
        ctx.lineTo(x, chartArea.bottom);
        ctx.stroke();
        ctx.fillStyle = color;
        ctx.fillText(key.toUpperCase(), x + 3, chartArea.top + 10);
        ctx.restore();
      }
    },
  };

  function unitAxis(unit) { return 'y_' + unit.replace(/[^a-z0-9]/gi, '_'); }

  function build() {
    if (chart) chart.destroy();
    const scales = { x: { type: 'linear', title: { display: true, text: 't (s)' } } };
    const datasets = [];
    let side = 0;
    channels.forEach((c, i) => {
      if (!selected.has(c.name)) return;
      const axis = unitAxis(c.unit);
      if (!scales[axis]) {
        scales[axis] = { type: 'linear', position: side++ % 2 ? 'right' : 'left',
                         title: { display: true, text: c.unit } };
      }
      datasets.push({ label: c.name, data: [], yAxisID: axis, borderColor: colors[i % colors.length],
                      borderWidth: 1.5, pointRadius: 0, spanGaps: false });
    });
    chart = new Chart($('scope'), {
      type: 'line',
      data: { datasets },
      options: {
        animation: false, parsing: false, normalized: true, responsive: true, maintainAspectRatio: false,
        interaction: { mode: 'nearest', intersect: false },
        plugins: { decimation: { enabled: true, algorithm: 'min-max' }, tooltip: { enabled: false } },
        scales,
        onClick: (e) => setCursor(chart.scales.x.getValueForPixel(e.x)),
      },
      plugins: [cursorPlugin],
    });
    dirty = true;
  }

  function setCursor(t) {
    cursors[cursors.next] = t;
    cursors.next = cursors.next === 'a' ? 'b' : 'a';
    readout();
    chart.draw();
  }

  function valueAt(name, t) {
    const s = chart.data.datasets.find((d) => d.label === name);
    const data = s ? s.data : [];
    if (!data.length) return null;
    let lo = 0, hi = data.length - 1;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (data[mid].x < t) lo = mid + 1; else hi = mid;
    }
    if (lo > 0 && Math.abs(data[lo - 1].x - t) < Math.abs(data[lo].x - t)) lo -= 1;
    return data[lo].y;
  }

  function fmt(v, digits = 4) { return v === null || Number.isNaN(v) ? '—' : Number(v).toPrecision(digits); }

  function readout() {
    const { a, b } = cursors;
    const parts = [];
    if (a !== null) parts.push(`A ${a.toFixed(3)} s`);
    if (b !== null) parts.push(`B ${b.toFixed(3)} s`);
    if (a !== null && b !== null) {
      parts.push(`Δt ${((b - a) * 1e3).toFixed(1)} ms`);
      for (const name of selected) {
        const va = valueAt(name, a), vb = valueAt(name, b);
        const d = va === null || vb === null ? null : vb - va;
        parts.push(`${name}: ${fmt(va)} → ${fmt(vb)} (Δ ${fmt(d)})`);
      }
    }
    $('cursor-readout').textContent = parts.length ? parts.join('  |  ') : 'click the plot: cursor A, then B';
  }

  function take(batch) {
    const n = batch.t.length;
    if (!n) return;
    for (let i = 0; i < n; i++) {
      const t = batch.t[i];
      const v = batch.v[i];
      channels.forEach((c, k) => series[c.name].push({ x: t, y: v[k] === null ? null : v[k] }));
    }
    const latest = batch.t[n - 1];
    page.lastT = latest;
    for (const c of channels) {
      const s = series[c.name];
      let cut = 0;
      while (cut < s.length && s[cut].x < latest - HISTORY_S) cut++;
      if (cut) s.splice(0, cut);
    }
    dirty = true;
  }

  function draw() {
    if (!chart || !dirty || page.paused || page.lastT === null) return;
    for (const d of chart.data.datasets) d.data = series[d.label].slice();
    chart.options.scales.x.min = page.lastT - HISTORY_S;
    chart.options.scales.x.max = page.lastT;
    chart.update('none');
    dirty = false;
    page.updates++;
    const now = performance.now();
    drawTimes.push(now);
    while (drawTimes.length && drawTimes[0] < now - RATE_WINDOW_MS) drawTimes.shift();
  }

  function rate() {
    const now = performance.now();
    while (drawTimes.length && drawTimes[0] < now - RATE_WINDOW_MS) drawTimes.shift();
    return drawTimes.length * 1000 / RATE_WINDOW_MS;
  }

  function init(list) {
    channels = list;
    const box = $('channels');
    box.textContent = '';
    for (const c of channels) {
      series[c.name] = [];
      const label = document.createElement('label');
      const cb = document.createElement('input');
      cb.type = 'checkbox';
      cb.value = c.name;
      cb.checked = selected.has(c.name);
      cb.addEventListener('change', () => {
        if (cb.checked) selected.add(c.name); else selected.delete(c.name);
        build();
        readout();
      });
      label.append(cb, ' ' + c.name);
      box.append(label);
    }
    build();
  }

  function points() {
    if (!chart) return 0;
    return chart.data.datasets.reduce((sum, d) => sum + d.data.length, 0);
  }

  return { init, take, draw, rate, points, readout };
})();

$('pause').addEventListener('click', () => {
  page.paused = !page.paused;
  $('pause').textContent = page.paused ? 'Resume' : 'Pause';
  if (!page.paused) scope.draw();
});
