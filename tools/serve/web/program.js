// The Program panel: a program pasted or loaded from a file, its preview
// (the path the server's interpreter makes of it from where the table
// stands, with the node's limits), its run from the tab with control (whole,
// or from a line), and while it runs the current line and the tool's
// position on the path.
'use strict';

const program = (() => {
  const SVG = 'http://www.w3.org/2000/svg';
  let posIndex = { x: 0, y: 1 };  // pos_x_mm, pos_y_mm in a telemetry sample (from /api/info)
  let pieces = [];                 // [{line, last, el}] as drawn
  let lit = null;                  // the piece of the current line
  let marker = null;               // the tool
  let textLines = [];              // the previewed program's lines
  let preview = null;
  let fitTravel = false;
  const files = { tool_table: null, var_file: null };  // the texts of the loaded tool table and .var file
  // What the page's browser test reads: linesSeen, the current lines of this tab's last run in order;
  // nodeStatesSeen, the node's PROGRAM_STATUS states of that run in order; pausesSeen, the pauses the
  // node reported (line and reason); total, the elements sent to the node.
  const state = page.program = { preview: null, drawn: 0, phase: 'idle', run: 0, line: 0, end: '',
                                 linesSeen: [], runStarted: -1, tool: null, error: '', pause: null,
                                 spindleTool: null, feedHold: false, nodeStatesSeen: [], pausesSeen: [], total: 0 };

  function el(name, attrs, parent) {
    const e = document.createElementNS(SVG, name);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    if (parent) parent.appendChild(e);
    return e;
  }

  function bounds(p) {
    if (fitTravel) return { x0: p.travel.x[0], x1: p.travel.x[1], y0: p.travel.y[0], y1: p.travel.y[1] };
    const b = { x0: p.start[0], x1: p.start[0], y0: p.start[1], y1: p.start[1] };
    for (const piece of p.pieces) {
      for (let i = 0; i < piece.points.length; i += 2) {
        b.x0 = Math.min(b.x0, piece.points[i]); b.x1 = Math.max(b.x1, piece.points[i]);
        b.y0 = Math.min(b.y0, piece.points[i + 1]); b.y1 = Math.max(b.y1, piece.points[i + 1]);
      }
    }
    return b;
  }

  // y up, as on the machine: the drawing is mirrored in y inside a group.
  function draw() {
    const svg = $('program-path');
    svg.replaceChildren();
    pieces = [];
    lit = null;
    marker = null;
    state.drawn = 0;
    const p = preview;
    if (!p) return;
    const b = bounds(p);
    const span = Math.max(b.x1 - b.x0, b.y1 - b.y0, 1e-3);
    const pad = 0.05 * span;
    svg.setAttribute('viewBox', `${b.x0 - pad} ${-(b.y1 + pad)} ${b.x1 - b.x0 + 2 * pad} ${b.y1 - b.y0 + 2 * pad}`);
    const g = el('g', { transform: 'scale(1,-1)' }, svg);
    el('rect', { x: p.travel.x[0], y: p.travel.y[0], width: p.travel.x[1] - p.travel.x[0],
                 height: p.travel.y[1] - p.travel.y[0], class: 'travel' }, g);
    for (const piece of p.pieces) {
      const pts = [];
      for (let i = 0; i < piece.points.length; i += 2) pts.push(`${piece.points[i]},${piece.points[i + 1]}`);
      const line = el('polyline', { points: pts.join(' '), class: 'path', 'data-line': piece.line }, g);
      const title = el('title', {}, line);
      title.textContent = piece.line === piece.last_line ? `line ${piece.line}` : `lines ${piece.line}–${piece.last_line}`;
      pieces.push({ line: piece.line, last: piece.last_line, el: line });
    }
    el('circle', { cx: p.start[0], cy: p.start[1], r: 0.008 * span, class: 'start' }, g);
    marker = el('circle', { cx: p.start[0], cy: p.start[1], r: 0.015 * span, class: 'tool' }, g);
    state.drawn = pieces.length;
    if (state.tool) moveTool(state.tool[0], state.tool[1]);
  }

  function moveTool(x, y) {
    if (!marker) return;
    marker.setAttribute('cx', x);
    marker.setAttribute('cy', y);
  }

  function light(line) {
    if (lit && line >= lit.line && line <= lit.last) return;
    if (lit) lit.el.classList.remove('current');
    lit = pieces.find((p) => line >= p.line && line <= p.last) || null;
    if (lit) lit.el.classList.add('current');
  }

  function show(p) {
    preview = state.preview = p;
    textLines = $('program-text').value.split('\n');
    const cycle = Number(p.cycle_time_s).toFixed(2);
    $('program-info').textContent = `${p.lines} lines, ${p.segments} segments, ${Number(p.length_mm).toFixed(1)} mm, ` +
      `programmed cycle time ${cycle} s from (${p.start[0].toFixed(3)}, ${p.start[1].toFixed(3)}) mm` +
      (p.thinned ? ` — ${p.note}` : '');
    draw();
  }

  // The request's body: the program, and a run from line when one is given (the server checks the values).
  function body() {
    const b = { gcode: $('program-text').value, optional_stop: $('program-optional-stop').checked,
                block_delete: $('program-block-delete').checked };
    if (files.tool_table !== null) b.tool_table = files.tool_table;
    if (files.var_file !== null) b.var_file = files.var_file;
    // A field the browser could not read as a number goes as text: the server refuses it, never runs the whole program.
    const field = (id) => ($(id).validity.badInput ? 'not a number' : $(id).value.trim());
    const as = (v) => (Number.isFinite(Number(v)) ? Number(v) : v);
    const from = field('program-from-line');
    if (from !== '') {
      b.from_line = as(from);
      const tool = field('program-tool');
      if (tool !== '') b.tool_in_spindle = as(tool);
    }
    return b;
  }

  async function previewNow() {
    say($('program-error'), 'interpreting…', true);
    const r = await api('POST', '/api/program/preview', body());
    state.error = r.ok ? '' : r.error;
    if (!r.ok) {
      preview = state.preview = null;
      draw();
      $('program-info').textContent = '';
      say($('program-error'), r.error, false);
      if (r.data && r.data.line > 0) selectLine(r.data.line);
      return false;
    }
    say($('program-error'), '', true);
    show(r.data);
    return true;
  }

  // The refused line, selected in the text box.
  function selectLine(n) {
    const box = $('program-text');
    const all = box.value.split('\n');
    let start = 0;
    for (let i = 0; i < n - 1 && i < all.length; i++) start += all[i].length + 1;
    box.focus();
    box.setSelectionRange(start, start + (all[n - 1] || '').length);
  }

  async function run() {
    if (!(await previewNow())) return;
    state.linesSeen = [];
    state.nodeStatesSeen = [];
    state.pausesSeen = [];
    state.total = 0;
    state.runStarted = -1;
    const r = await api('POST', '/api/program/run', body());
    state.error = r.ok ? '' : r.error;
    if (r.ok) state.runStarted = r.data.program.run;
    say($('program-error'), r.ok ? '' : r.error, r.ok);
  }

  // Every telemetry event: the tool where the node says it is, the program's state.
  function take(ev) {
    if (ev.v && ev.v.length) {
      const last = ev.v[ev.v.length - 1];
      const x = last[posIndex.x];
      const y = last[posIndex.y];
      if (x !== null && y !== null) {
        state.tool = [x, y];
        moveTool(x, y);
      }
    }
    const s = ev.program;
    if (!s) return;
    state.phase = s.phase;
    state.run = s.run;
    state.end = s.end;
    if (s.phase !== 'idle' && s.line > 0) {
      state.line = s.line;
      if (s.run === state.runStarted && state.linesSeen[state.linesSeen.length - 1] !== s.line) state.linesSeen.push(s.line);
      light(s.line);
    }
    let text = '';
    if (s.phase === 'starting') text = 'starting…';
    else if (s.phase === 'running') {
      text = `running line ${s.line}: ${(textLines[s.line - 1] || '').trim()} — element ${s.element}/${s.total}, ` +
        `${(100 * s.fraction).toFixed(1)} %` + (s.underruns ? `, underruns ${s.underruns}` : '') +
        (s.interrupting ? ' — stopping' : '');
      if (s.node_state === 'holding') text = `feed held at line ${s.line} — Feed resume goes on, Stop ends the program`;
      if (s.pause) text = `paused at ${s.pause.text} — Resume continues, Stop ends the program`;
    } else if (s.phase === 'ended') {
      text = `run ${s.run} ${s.end}` + (s.line ? ` at line ${s.line}` : '') + (s.message ? `: ${s.message}` : '');
    }
    // The tool the node knows in the spindle (PROGRAM_TOOL), as the run last reported it.
    state.spindleTool = s.spindle_tool || null;
    if (text && s.spindle_tool) text += ` — in the spindle: ${s.spindle_tool.text}`;
    state.pause = s.pause || null;
    if (s.run === state.runStarted) {
      const seen = state.nodeStatesSeen;
      if (s.node_state && seen[seen.length - 1] !== s.node_state) seen.push(s.node_state);
      const last = state.pausesSeen[state.pausesSeen.length - 1];
      if (s.pause && !(last && last.line === s.pause.line && last.reason === s.pause.reason))
        state.pausesSeen.push({ line: s.pause.line, reason: s.pause.reason });
      if (s.total) state.total = s.total;
    }
    $('program-resume').hidden = !(s.phase === 'running' && s.pause);
    state.feedHold = !!s.feed_hold;
    $('program-hold').hidden = s.phase !== 'running';
    $('program-hold').textContent = s.feed_hold ? 'Feed resume' : 'Feed hold';
    $('program-state').textContent = text;
    $('program-state').classList.toggle('refusal', s.phase === 'ended' && s.end !== 'done');
  }

  function init(channels) {
    posIndex = { x: channels.findIndex((c) => c.name === 'pos_x_mm'), y: channels.findIndex((c) => c.name === 'pos_y_mm') };
  }

  $('program-preview').addEventListener('click', previewNow);
  $('program-run').addEventListener('click', run);
  $('program-stop').addEventListener('click', async () => {
    const r = await api('POST', '/api/motion', { kind: 'stop' });
    say($('program-error'), r.ok ? '' : r.error, r.ok);
  });
  $('program-resume').addEventListener('click', async () => {
    const r = await api('POST', '/api/program/resume', {});
    say($('program-error'), r.ok ? '' : r.error, r.ok);
  });
  $('program-hold').addEventListener('click', async () => {
    const r = await api('POST', '/api/program/hold', { hold: !state.feedHold });
    say($('program-error'), r.ok ? '' : r.error, r.ok);
  });
  $('program-fit').addEventListener('click', () => {
    fitTravel = !fitTravel;
    $('program-fit').textContent = fitTravel ? 'Fit path' : 'Show travel';
    draw();
  });
  for (const [id, key] of [['program-tool-table', 'tool_table'], ['program-var-file', 'var_file']]) {
    $(id).addEventListener('change', async (e) => {
      const file = e.target.files[0];
      files[key] = file ? await file.text() : null;
      if ($('program-text').value.trim() !== '') previewNow();
    });
  }
  $('program-file').addEventListener('change', async (e) => {
    const file = e.target.files[0];
    if (!file) return;
    $('program-text').value = await file.text();
    previewNow();
  });

  return { init, take, preview: previewNow };
})();
