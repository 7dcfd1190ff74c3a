// The page's start: node info, the scope's channels, the stream, the tables.
'use strict';

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
  if (info.data.read_only) $('node-info').textContent += ' (read-only server: watch only)';
  scope.init(info.data.channels);
  program.init(info.data.channels);
  startHeartbeat(info.data.deadman_ms || 300);
  connect();
  const c = await api('GET', '/api/control');
  if (c.ok) showControl(c.data);
  params.load();
  captures.list();
})();
