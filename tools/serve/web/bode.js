// The Bode view: a frequency-response result (measured, or a saved file).
'use strict';

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
    const line = (mm) =>
      `gain margin ${f(mm.gain_db, 'dB')}   phase margin ${f(mm.phase_deg, '°')}   crossover ${f(mm.crossover_hz, 'Hz', 2)}`;
    // The model's margins beside the measured ones when the result has them (tnvctl freq-response --json).
    $('margins').textContent = line(m) + (data.model_margins ? `   |   model: ${line(data.model_margins)}` : '');
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
