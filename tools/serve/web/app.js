// The TNV-40 tuning page: scope, parameters, faults, captures, Bode view.
// Plain JavaScript and Debian's Chart.js; everything it knows comes from
// tnvctl serve's /api endpoints (tools/serve/tuning_server.cpp).
'use strict';

const HISTORY_S = 10;          // the scope keeps and shows this much
const RATE_WINDOW_MS = 1000;   // the update counter counts over this window

// One token per browser tab: browser control is keyed on it.
const token = (() => {
  let t = sessionStorage.getItem('tnv-token');
  if (!t) {
    const bytes = new Uint8Array(16);
    crypto.getRandomValues(bytes);
    t = Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join('');
    sessionStorage.setItem('tnv-token', t);
  }
  return t;
})();

const $ = (id) => document.getElementById(id);

// What the page exposes to its own browser test (and to a curious user's console).
const page = window.tnvPage = {
  events: 0, updates: 0, updatesPerS: 0, lastT: null, paused: false,
  control: { you: false, taken: false }, bode: null, points: () => scope.points(),
};

async function api(method, path, body) {
  const init = { method, headers: { 'X-Tnv-Token': token } };
  if (body !== undefined) {
    init.headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  let res;
  try {
    res = await fetch(path, init);
  } catch (e) {
    return { ok: false, status: 0, error: 'the server does not answer (is tnvctl serve running?)' };
  }
  let data = null;
  try { data = await res.json(); } catch (e) { data = null; }
  const error = res.ok ? '' : (data && data.error) ? data.error : `HTTP ${res.status}`;
  return { ok: res.ok, status: res.status, data, error };
}

// A message in its place: a refusal in red, anything else plain.
function say(el, text, ok) {
  el.textContent = text;
  el.classList.toggle('refusal', !ok);
  el.classList.toggle('ok', ok);
}

// ---------------------------------------------------------------- scope
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

// ------------------------------------------------- status, faults, control
function showStatus(status) {
  const hb = status.heartbeat;
  const faulted = hb && hb.state === 'faulted';
  $('fault-banner').hidden = !faulted;
  if (faulted) {
    let text = hb.fault;
    const ev = status.fault;
    if (ev && ev.reason === hb.fault) {
      if (ev.axis) text += ` on axis ${ev.axis}`;
      text += ` (value ${Number(ev.value).toPrecision(4)})`;
    }
    $('fault-reason').textContent = text;
  }
  const link = $('link-state');
  if (status.bus_error) {
    link.textContent = 'bus error: ' + status.bus_error;
    link.className = 'state-bad';
  } else if (hb) {
    link.textContent = `${hb.state}` + (hb.owner ? ` (owner host ${hb.owner})` : '');
    link.className = faulted ? 'state-bad' : 'state-ok';
  }
}

function showControl(control) {
  page.control = control;
  const state = $('control-state');
  if (control.you) {
    state.textContent = 'you have control';
    state.className = 'mine';
  } else {
    state.textContent = control.taken ? 'read only: another browser has control' : 'read only';
    state.className = '';
  }
  $('take-control').hidden = control.you;
  $('release-control').hidden = !control.you;
  document.body.classList.toggle('read-only', !control.you);
}

$('take-control').addEventListener('click', async () => {
  const r = await api('POST', '/api/control/take');
  $('control-error').textContent = r.ok ? '' : r.error;
  if (r.ok) showControl(r.data);
});
$('release-control').addEventListener('click', async () => {
  const r = await api('POST', '/api/control/release');
  if (r.ok) showControl(r.data);
});
$('clear-fault').addEventListener('click', async () => {
  const r = await api('POST', '/api/fault/clear');
  say($('fault-error'), r.ok ? '' : r.error, r.ok);
});

for (const b of document.querySelectorAll('[data-motion]')) {
  b.classList.add('needs-control');
  b.addEventListener('click', async () => {
    const body = { kind: b.dataset.motion };
    if (body.kind === 'move') {
      body.axis = b.dataset.axis;
      body.distance_mm = Number(b.dataset.distance);
      body.speed_mm_s = Number($('move-speed').value);
    }
    const r = await api('POST', '/api/motion', body);
    say($('motion-error'), r.ok ? '' : r.error, r.ok);
  });
}

// ------------------------------------------------------------ telemetry
function connect() {
  const source = new EventSource('/api/telemetry?token=' + encodeURIComponent(token));
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    page.events++;
    scope.take(ev);
    scope.draw();
    showStatus(ev.status);
    showControl(ev.control);
  };
  source.onerror = () => {
    $('link-state').textContent = 'telemetry lost: reconnecting…';
    $('link-state').className = 'state-bad';
  };
}

setInterval(() => {
  page.updatesPerS = scope.rate();
  $('rate').textContent = page.paused ? 'paused' : `${page.updatesPerS.toFixed(0)} updates/s`;
}, 250);

// ----------------------------------------------------------- parameters
const params = (() => {
  const tbody = document.querySelector('#params tbody');

  function row(p) {
    const tr = document.createElement('tr');
    tr.dataset.param = p.name;
    const cell = (text, cls) => {
      const td = document.createElement('td');
      td.textContent = text;
      if (cls) td.className = cls;
      tr.append(td);
      return td;
    };
    const name = cell(p.name);
    name.title = p.doc + (p.safety ? ' (safety parameter: commissioning mode only)' : '') + ` [apply: ${p.apply}]`;
    cell(p.text, 'value');
    cell(p.unit);
    cell(p.range);
    cell(p.staged || '', 'staged');
    const inputCell = cell('');
    const setCell = cell('');
    const stageCell = cell('');
    const msg = cell('', 'msg');
    if (p.access === 'rw') {
      const input = document.createElement('input');
      input.value = p.text;
      input.className = 'needs-control';
      inputCell.append(input);
      const set = document.createElement('button');
      set.textContent = 'Set';
      set.className = 'set needs-control';
      set.addEventListener('click', () => change('/api/params/set', tr, input.value));
      setCell.append(set);
      const stage = document.createElement('button');
      stage.textContent = 'Stage';
      stage.className = 'stage needs-control';
      stage.addEventListener('click', () => change('/api/params/stage', tr, input.value));
      stageCell.append(stage);
      input.addEventListener('keydown', (e) => { if (e.key === 'Enter') change('/api/params/set', tr, input.value); });
    }
    msg.dataset.role = 'msg';
    return tr;
  }

  function rowOf(name) { return tbody.querySelector(`tr[data-param="${CSS.escape(name)}"]`); }

  function showApplied(applied) {
    for (const a of applied) {
      const tr = rowOf(a.name);
      if (!tr) continue;
      tr.querySelector('td.value').textContent = a.text;
      tr.classList.add('changed');
      say(tr.querySelector('td.msg'), 'read back ' + a.text, true);
    }
  }

  function showStaged(staged) {
    for (const tr of tbody.rows) tr.querySelector('td.staged').textContent = staged[tr.dataset.param] || '';
    const n = Object.keys(staged).length;
    $('commit').disabled = n === 0;
    $('discard').disabled = n === 0;
    $('staged-list').textContent = n ? `${n} staged` : '';
  }

  async function change(path, tr, value) {
    const msg = tr.querySelector('td.msg');
    say(msg, '…', true);
    const r = await api('POST', path, { name: tr.dataset.param, value });
    if (!r.ok) {
      say(msg, r.error, false);
      return;
    }
    if (r.data.applied) showApplied(r.data.applied);
    if (r.data.staged) {
      showStaged(r.data.staged);
      say(msg, 'staged', true);
    }
  }

  async function load() {
    const r = await api('GET', '/api/params');
    if (!r.ok) {
      say($('commit-error'), r.error, false);
      return;
    }
    tbody.textContent = '';
    for (const p of r.data.params) tbody.append(row(p));
    showStaged(r.data.staged);
    filter();
  }

  function filter() {
    const f = $('param-filter').value.trim();
    for (const tr of tbody.rows) tr.hidden = f !== '' && !tr.dataset.param.includes(f);
  }

  $('param-filter').addEventListener('input', filter);
  $('param-refresh').addEventListener('click', load);
  $('commit').addEventListener('click', async () => {
    const r = await api('POST', '/api/params/commit');
    say($('commit-error'), r.ok ? '' : r.error, r.ok);
    if (r.ok) showApplied(r.data.applied);
    // Applied or refused, the node's staged set is gone.
    if (r.ok || r.status === 409) showStaged({});
  });
  $('discard').addEventListener('click', async () => {
    const r = await api('POST', '/api/params/discard');
    say($('commit-error'), r.ok ? '' : r.error, r.ok);
    if (r.ok) showStaged(r.data.staged);
  });
  return { load };
})();

// ------------------------------------------------------------- captures
const captures = (() => {
  let chart = null;

  async function list() {
    const r = await api('GET', '/api/captures');
    if (!r.ok) return;
    const ul = $('capture-list');
    ul.textContent = '';
    for (const c of r.data.captures) {
      const li = document.createElement('li');
      li.dataset.capture = c.id;
      li.append(`#${c.id}: ${c.samples} samples every ${(c.period_s * 1e3).toFixed(0)} ms (${c.channels.join(', ')}) `);
      const draw = document.createElement('button');
      draw.textContent = 'Draw';
      draw.addEventListener('click', () => show(c.id));
      const csv = document.createElement('a');
      csv.href = `/api/captures/${c.id}.csv`;
      csv.download = `capture-${c.id}.csv`;
      csv.textContent = 'CSV';
      li.append(draw, ' ', csv);
      ul.append(li);
    }
  }

  async function show(id) {
    const r = await api('GET', `/api/captures/${id}`);
    if (!r.ok) {
      say($('capture-state'), r.error, false);
      return;
    }
    const t = r.data.t_s;
    const datasets = Object.entries(r.data.columns).map(([name, col], i) => ({
      label: name, data: col.map((y, k) => ({ x: t[k], y })), pointRadius: 0, borderWidth: 1.2,
      borderColor: ['#1f6feb', '#d1242f', '#1a7f37', '#9a6700', '#8250df'][i % 5],
    }));
    if (chart) chart.destroy();
    chart = new Chart($('capture-chart'), {
      type: 'line',
      data: { datasets },
      options: {
        animation: false, parsing: false, normalized: true, maintainAspectRatio: false,
        plugins: { decimation: { enabled: true, algorithm: 'lttb', samples: 800 },
                   title: { display: true, text: `capture #${id}` } },
        scales: { x: { type: 'linear', title: { display: true, text: 't (s)' } } },
      },
    });
  }

  $('capture-take').addEventListener('click', async () => {
    const body = { decimation: Number($('capture-decimation').value),
                   duration_s: Number($('capture-duration').value) };
    const ch = $('capture-channels').value.trim();
    if (ch) body.channels = ch;
    say($('capture-state'), 'recording and uploading…', true);
    const r = await api('POST', '/api/captures', body);
    if (!r.ok) {
      say($('capture-state'), r.error, false);
      return;
    }
    say($('capture-state'), `capture #${r.data.id}: ${r.data.samples} samples, uploaded in ${r.data.upload_s.toFixed(2)} s`, true);
    await list();
    show(r.data.id);
  });
  $('capture-take').classList.add('needs-control');
  return { list };
})();

// ----------------------------------------------------------------- Bode
const bode = (() => {
  let gainChart = null;
  let phaseChart = null;

  // The result JSON of the frequency-response measurement (tnvctl ... --json).
  function check(data) {
    if (!data || !Array.isArray(data.points) || !data.points.length) return 'no "points" in the JSON';
    for (const p of data.points)
      for (const k of ['freq_hz', 'gain_db', 'phase_deg', 'coherence'])
        if (typeof p[k] !== 'number') return `a point has no number "${k}"`;
    return '';
  }

  const crossoverPlugin = {
    id: 'tnvCrossover',
    afterDraw(c) {
      const f = c.options.plugins.tnvCrossover && c.options.plugins.tnvCrossover.hz;
      if (!f) return;
      const x = c.scales.x.getPixelForValue(f);
      const ctx = c.ctx;
      ctx.save();
      ctx.strokeStyle = '#9a6700';
      ctx.setLineDash([4, 4]);
      ctx.beginPath();
      ctx.moveTo(x, c.chartArea.top);
      ctx.lineTo(x, c.chartArea.bottom);
      ctx.stroke();
      ctx.restore();
    },
  };

  // Both charts' y axes equally wide, so their frequency axes line up.
  const fixedWidth = (scale) => { scale.width = 56; };

  function logAxis() {
    return { type: 'logarithmic', title: { display: true, text: 'f (Hz)' } };
  }

  function draw(data) {
    const error = check(data);
    if (error) {
      say($('bode-error'), 'cannot draw: ' + error, false);
      return;
    }
    say($('bode-error'), '', true);
    const pts = data.points;
    const xy = (key) => pts.filter((p) => typeof p[key] === 'number').map((p) => ({ x: p.freq_hz, y: p[key] }));
    const m = data.margins || {};
    const crossover = typeof m.crossover_hz === 'number' ? m.crossover_hz : null;
    if (gainChart) gainChart.destroy();
    if (phaseChart) phaseChart.destroy();
    const gainSets = [
      { label: 'gain (dB)', data: xy('gain_db'), borderColor: '#1f6feb', pointRadius: 2, yAxisID: 'y' },
      { label: 'coherence', data: xy('coherence'), borderColor: '#6e7781', borderDash: [3, 3], pointRadius: 0,
        yAxisID: 'coh' },
    ];
    const phaseSets = [{ label: 'phase (deg)', data: xy('phase_deg'), borderColor: '#d1242f', pointRadius: 2 }];
    if (pts.some((p) => typeof p.model_gain_db === 'number'))
      gainSets.push({ label: 'model gain (dB)', data: xy('model_gain_db'), borderColor: '#1a7f37', pointRadius: 0 });
    if (pts.some((p) => typeof p.model_phase_deg === 'number'))
      phaseSets.push({ label: 'model phase (deg)', data: xy('model_phase_deg'), borderColor: '#1a7f37', pointRadius: 0 });
    const common = { animation: false, parsing: false, maintainAspectRatio: false,
                     plugins: { tnvCrossover: { hz: crossover } } };
    gainChart = new Chart($('bode-gain'), {
      type: 'line', data: { datasets: gainSets }, plugins: [crossoverPlugin],
      options: { ...common, scales: { x: logAxis(), y: { title: { display: true, text: 'dB' }, afterFit: fixedWidth },
                                      coh: { position: 'right', min: 0, max: 1, grid: { drawOnChartArea: false },
                                             title: { display: true, text: 'coherence' }, afterFit: fixedWidth } } },
    });
    phaseChart = new Chart($('bode-phase'), {
      type: 'line', data: { datasets: phaseSets }, plugins: [crossoverPlugin],
      options: { ...common, scales: { x: logAxis(), y: { title: { display: true, text: 'deg' }, afterFit: fixedWidth },
                                      pad: { position: 'right', display: true, grid: { drawOnChartArea: false },
                                             ticks: { display: false }, afterFit: fixedWidth } } },
    });
    const f = (v, unit, d = 1) => (typeof v === 'number' ? `${v.toFixed(d)} ${unit}` : '—');
    $('margins').textContent =
      `gain margin ${f(m.gain_db, 'dB')}   phase margin ${f(m.phase_deg, '°')}   crossover ${f(m.crossover_hz, 'Hz', 2)}`;
    page.bode = { points: pts.length, margins: m };
  }

  $('bode-measure').classList.add('needs-control');
  $('bode-measure').addEventListener('click', async () => {
    say($('bode-error'), 'measuring…', true);
    const r = await api('POST', '/api/freq-response', { axis: $('bode-axis').value, loop: $('bode-loop').value });
    if (!r.ok) {
      say($('bode-error'), `${r.error} (HTTP ${r.status})`, false);
      return;
    }
    draw(r.data);
  });
  $('bode-file').addEventListener('change', () => {
    const file = $('bode-file').files[0];
    if (!file) return;
    const reader = new FileReader();
    reader.onload = () => {
      let data;
      try {
        data = JSON.parse(reader.result);
      } catch (e) {
        say($('bode-error'), `${file.name}: not JSON (${e.message})`, false);
        return;
      }
      draw(data);
    };
    reader.readAsText(file);
  });
  return { draw };
})();

// ---------------------------------------------------------------- start
(async () => {
  if (typeof Chart === 'undefined') {
    $('node-info').textContent = 'Chart.js did not load (libjs-chart.js, tnvctl serve --js-dir)';
    return;
  }
  const info = await api('GET', '/api/info');
  if (!info.ok) {
    $('node-info').textContent = info.error;
    return;
  }
  $('node-info').textContent = `node ${info.data.node} on ${info.data.bus}, host id ${info.data.host_id}`;
  scope.init(info.data.channels);
  connect();
  const c = await api('GET', '/api/control');
  if (c.ok) showControl(c.data);
  params.load();
  captures.list();
})();
