// Captures: record, draw, download as CSV.
'use strict';

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
