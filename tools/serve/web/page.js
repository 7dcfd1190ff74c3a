// The TNV-40 tuning page: what every part shares (the tab's token, the
// /api calls of tnvctl serve, messages). Plain scripts, loaded in order by
// index.html, with Debian's Chart.js; no build step.
'use strict';

// One token per browser tab: browser control is keyed on it. (Not the
// server's secret: that lives in an HttpOnly cookie the scripts never see.)
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
