// The parameter table: read, filter, set, stage, commit, discard; each
// refusal's reason next to its row.
'use strict';

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
