// Dataset folder (casmap dataset --out DIR): the manifest as a filterable table and a sample's
// maps (from its HDF5 run file, or TIFFs beside it) on click.
'use strict';

// Scalar leaves of a manifest line as "a.b.c" -> value (SHA-256 digests left out).
const flatten = (obj, prefix = '', out = {}) => {
  for (const [k, v] of Object.entries(obj)) {
    const key = prefix ? prefix + '.' + k : k;
    if (v !== null && typeof v === 'object' && !Array.isArray(v)) flatten(v, key, out);
    else if (!/sha256|^files$|^simulate$/.test(key)) out[key] = Array.isArray(v) ? JSON.stringify(v) : v;
  }
  return out;
};

// The files of a manifest line with one of `exts`, as paths under DIR: `files[].path` are
// relative to the sample's `dir` (casmap dataset); other strings naming files are taken as is.
const filesIn = (line, exts) => {
  const out = [];
  const want = (v) => typeof v === 'string' && exts.some((e) => v.endsWith(e));
  for (const f of Array.isArray(line.files) ? line.files : []) {
    if (want(f.path)) out.push(line.dir ? line.dir + '/' + f.path : f.path);
  }
  if (Array.isArray(line.files)) return out;
  const walk = (obj) => {
    for (const v of Object.values(obj)) {
      if (want(v)) out.push(v);
      else if (v && typeof v === 'object') walk(v);
    }
  };
  walk(line);
  return out;
};

cm.showSample = async (body, line) => {
  body.replaceChildren(cm.el('p', { class: 'hint' }, 'loading sample…'));
  const runs = filesIn(line, ['.h5']);
  const layers = [];
  let grid = null;
  if (runs.length > 0) {
    const info = await cm.json('/api/run?' + cm.q({ path: runs[0] }));
    grid = info.grid;
    const order = ['elevation_m', 'truth_m', 'filtered/cas', 'filtered/wiener', 'filtered/average',
      'filtered/median', 'filtered/cwm'];
    const rank = (n) => (order.includes(n) ? order.indexOf(n) : order.length);
    for (const name of info.layers.slice().sort((a, b) => rank(a) - rank(b))) {
      layers.push({
        name, label: name === 'elevation_m' ? 'raw h' : name.replace(/^filtered\//, '').replace(/_m$/, ''),
        kind: cm.layerKind(name),
        unit: cm.layerKind(name) === 'elevation' ? 'm' : '',
        map: await cm.map('/api/runmap?' + cm.q({ path: runs[0], layer: name })),
      });
    }
  }
  for (const tif of filesIn(line, ['.tif', '.tiff'])) {
    const name = tif.split('/').pop().replace(/\.tiff?$/, '');
    layers.push({ name, label: name, kind: cm.layerKind(name),
      unit: cm.layerKind(name) === 'elevation' ? 'm' : '',
      map: await cm.map('/api/map?' + cm.q({ path: tif })) });
  }
  const shape = layers[0] ? [layers[0].map.rows, layers[0].map.cols] : null;
  const same = layers.filter((l) => l.map.rows === shape[0] && l.map.cols === shape[1]);
  const viewer = cm.el('div', {});
  body.replaceChildren(viewer, cm.el('pre', {}, JSON.stringify(line, null, 1)));
  if (same.length === 0) viewer.append(cm.el('p', { class: 'hint' }, 'no maps in this sample'));
  else cm.mapViewer(viewer, same, grid);
  for (const yaml of filesIn(line, ['.yaml'])) {
    try {
      body.append(cm.el('h3', {}, yaml), cm.el('pre', {}, await cm.text(cm.files(yaml))));
    } catch (e) { /* a scene listed but not written (failed sample) */ }
  }
};

cm.showDataset = async () => {
  const text = await cm.text('/files/manifest.jsonl');
  // Seeds are uint64: keep integers beyond 2^53 exact by reading them as strings.
  const lines = text.split('\n').filter((l) => l.trim() !== '')
    .map((l) => JSON.parse(l.replace(/([:[,]\s*)(\d{16,})(?=\s*[,}\]])/g, '$1"$2"')));
  const rows = lines.map((l, i) => ({ ...flatten(l), __line: l, __key: String(l.index ?? i) }));
  const keys = [...new Set(rows.flatMap((r) => Object.keys(r).filter((k) => !k.startsWith('__'))))];
  const columns = keys.map((k) => ({ key: k, label: k, digits: 4,
    text: rows.some((r) => typeof r[k] === 'string'), value: (r) => r[k] ?? null }));

  const spec = cm.section('Dataset', 'dataset');
  spec.append(cm.el('p', {}, `${lines.length} samples in manifest.jsonl`));
  if (await cm.exists('/files/dataset.yaml')) {
    spec.append(cm.el('details', {}, cm.el('summary', {}, 'dataset.yaml'),
      cm.el('pre', {}, await cm.text('/files/dataset.yaml'))));
  }
  const man = cm.section('Manifest', 'manifest');
  const filter = cm.el('input', { id: 'manifest-filter', size: 50,
    placeholder: 'filter: words or key=value, e.g. split=train rig' });
  const count = cm.el('span', { id: 'manifest-count' });
  const sample = cm.section('Sample', 'sample');
  const body = cm.el('div', { id: 'sample-body' }, cm.el('p', { class: 'hint' }, 'click a sample'));
  sample.append(body);
  const table = cm.table(columns, rows, { id: 'manifest-table',
    onRow: (r) => cm.showSample(body, r.__line).catch((e) => cm.error(body, e)) });
  const apply = () => {
    const terms = filter.value.trim().toLowerCase().split(/\s+/).filter(Boolean);
    const kept = rows.filter((r) => terms.every((t) => {
      const eq = t.indexOf('=');
      if (eq > 0) {
        const [k, v] = [t.slice(0, eq), t.slice(eq + 1)];
        return Object.entries(r).some(([key, val]) => !key.startsWith('__') &&
          key.toLowerCase().endsWith(k) && String(val).toLowerCase() === v);
      }
      return Object.entries(r).some(([key, val]) => !key.startsWith('__') &&
        String(val).toLowerCase().includes(t));
    }));
    table.setRows(kept);
    count.textContent = `${kept.length} of ${rows.length}`;
  };
  filter.addEventListener('input', apply);
  man.append(cm.el('div', { class: 'toolbar' }, filter, count), cm.el('div', { class: 'scroll' }, table));
  apply();
};
