// The dead-man rule's heartbeat, in a worker: off the page's main thread,
// so a busy page (charts redrawing on a loaded machine) does not delay it,
// and not throttled as a hidden page's timers are. The page tells it when
// this tab has control; a closed tab ends it with the page.
'use strict';

let state = { you: false, token: '', periodMs: 75 };
let timer = null;

async function beat() {
  if (!state.you) return;
  try {
    const r = await fetch('/api/control/heartbeat', { method: 'POST', headers: { 'X-Tnv-Token': state.token } });
    if (r.status === 403 && state.you) postMessage({ lost: true });
  } catch (e) {
    // The server is gone: the page's telemetry stream says so.
  }
}

onmessage = (e) => {
  state = e.data;
  if (timer !== null) clearInterval(timer);
  timer = state.you ? setInterval(beat, state.periodMs) : null;
  if (state.you) beat();
};
