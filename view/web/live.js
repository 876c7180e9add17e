// Live folder (casmap live --out DIR): status.json polled twice a second (scans/s, latency p99,
// dropped scans, CRC errors, ...) and the snapshot TIFFs reloaded when they change.
'use strict';

// The status fields shown first, by the names casmap live may use for them.
const kLiveFields = [
  ['scans', ['scans', 'scans_received', 'scan_count', 'scans_total']],
  ['scans/s', ['scans_per_s', 'scan_rate_hz', 'rate_hz']],
  ['latency p99', ['latency_p99_ms', 'latency_p99_us', 'latency_p99_s', 'p99_ms', 'p99_us']],
  ['dropped scans', ['dropped_scans', 'dropped']],
  ['CRC errors', ['crc_errors', 'crc']],
];

cm.showLive = async () => {
  const status = cm.section('Live status', 'live');
  const metrics = cm.el('div', { class: 'metrics', id: 'live-metrics' });
  const stamp = cm.el('p', { class: 'hint', id: 'live-updated' });
  status.append(metrics, stamp);
  const mapsSection = cm.section('Active window and obstacle map', 'live-maps');
  const maps = cm.el('div', { id: 'live-map-body' }, cm.el('p', { class: 'hint' }, 'waiting for snapshots…'));
  mapsSection.append(maps);
  let lastMaps = '';
  let busy = false;

  const showStatus = (s) => {
    const cards = [];
    const used = new Set();
    for (const [label, names] of kLiveFields) {
      const key = names.find((n) => n in s);
      if (key === undefined) continue;
      used.add(key);
      const unit = /_per_s$|_hz$/.test(key) ? ' /s' : /_ms$/.test(key) ? ' ms'
        : /_us$/.test(key) ? ' µs' : /_s$/.test(key) ? ' s' : '';
      cards.push(cm.el('div', { class: 'metric', id: 'live-' + label.replace(/[^a-z0-9]+/gi, '-') },
        cm.el('div', { class: 'v', dataset: { key, value: String(s[key]) } }, cm.fmt(s[key], 2) + unit),
        cm.el('div', { class: 'k' }, label)));
    }
    for (const [k, v] of Object.entries(s)) {
      if (used.has(k) || (typeof v === 'object' && v !== null)) continue;
      cards.push(cm.el('div', { class: 'metric' }, cm.el('div', { class: 'v', dataset: { key: k } },
        cm.fmt(v, 3)), cm.el('div', { class: 'k' }, k)));
    }
    metrics.replaceChildren(...cards);
    stamp.textContent = 'updated ' + new Date().toLocaleTimeString();
  };

  // Snapshot TIFFs in DIR and DIR/snapshots, reloaded when a file's mtime or size changes.
  const refreshMaps = async () => {
    const found = [];
    for (const dir of ['', 'snapshots']) {
      let list;
      try { list = await cm.json('/api/list?' + cm.q({ path: dir })); } catch (e) { continue; }
      for (const e of list.entries) {
        if (!e.dir && /\.tiff?$/.test(e.name)) found.push({ ...e, path: dir ? dir + '/' + e.name : e.name });
      }
    }
    const sig = found.map((f) => `${f.path}:${f.mtime_ns}:${f.bytes}`).join('|');
    if (sig === lastMaps || found.length === 0) return;
    lastMaps = sig;
    const layers = [];
    for (const f of found) {
      try {
        const name = f.name.replace(/\.tiff?$/, '');
        const kind = /certainty/.test(name) ? 'certainty' : /obstacle/.test(name) ? 'other' : 'elevation';
        layers.push({ name, label: name, kind, unit: kind === 'elevation' ? 'm' : '',
          map: await cm.map('/api/map?' + cm.q({ path: f.path })) });
      } catch (e) { /* replaced while reading: next poll */ }
    }
    // Panels of one shape share a viewer (window layers; the obstacle map has its own grid).
    maps.replaceChildren();
    const shapes = new Map();
    for (const l of layers) {
      const k = l.map.rows + 'x' + l.map.cols;
      if (!shapes.has(k)) shapes.set(k, []);
      shapes.get(k).push(l);
    }
    let n = 0;
    for (const group of shapes.values()) {
      const box = cm.el('div', {});
      maps.append(box);
      cm.mapViewer(box, group, null, { infoId: 'cell-info' + (n++ ? '-' + n : '') });
    }
  };

  const tick = async () => {
    if (busy) return;
    busy = true;
    try {
      showStatus(await cm.json('/files/status.json'));
      await refreshMaps();
    } catch (e) {
      stamp.textContent = 'waiting for status.json… (' + e.message + ')';
    } finally {
      busy = false;
    }
  };
  await tick();
  setInterval(tick, 500);
};
