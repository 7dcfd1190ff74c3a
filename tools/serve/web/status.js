// The node's state, the fault banner, browser control, the motion buttons and
// the telemetry stream that feeds the scope and all of them.
'use strict';

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
  showSpindle(status.spindle);
}

// The spindle, shown only: starting it stays with tnvctl, a program or the
// Python module (docs/tuning-guide.md "Spindle").
function showSpindle(spindle) {
  const el = $('spindle-state');
  if (!spindle) {
    el.textContent = 'spindle: not streamed (tlm.spindle_ms = 0)';
    el.className = '';
    return;
  }
  let text = `spindle: ${spindle.state.replace('_', ' ')} ${Math.round(spindle.measured_rpm)} rpm`;
  if (spindle.commanded_on) text += ` (${spindle.direction}, command ${Math.round(spindle.command_rpm)} rpm)`;
  else if (spindle.stop_cause !== 'none') text += ` (stopped: ${spindle.stop_cause})`;
  el.textContent = text;
  el.className = spindle.state === 'inhibited' ? 'state-bad' : spindle.state === 'at_speed' ? 'state-ok' : '';
}

function showControl(control) {
  page.control = control;
  tellHeartbeat(control.you);
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

// The dead-man rule: while this tab has control, a worker (heartbeat.js)
// says so every quarter of the server's dead-man time (/api/info); a tab
// that stops (closed, asleep, offline) loses control and the server stops
// the motion it started.
const heartbeat = { worker: new Worker('heartbeat.js'), periodMs: 75, you: false };
heartbeat.worker.onmessage = () => {
  showControl({ you: false, taken: false });
  $('control-error').textContent = 'control lost: this page went quiet for too long';
};
function startHeartbeat(deadmanMs) {
  heartbeat.periodMs = Math.max(20, Math.floor(deadmanMs / 4));
}
function tellHeartbeat(you) {
  if (you === heartbeat.you) return;
  heartbeat.you = you;
  heartbeat.worker.postMessage({ you, token, periodMs: heartbeat.periodMs });
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

function connect() {
  const source = new EventSource('/api/telemetry?token=' + encodeURIComponent(token));
  source.onmessage = (e) => {
    const ev = JSON.parse(e.data);
    page.events++;
    scope.take(ev);
    scope.draw();
    program.take(ev);
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
