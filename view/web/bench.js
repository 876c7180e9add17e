// Benchmark folder (casmap bench --out DIR): Fig. 8 chart, PI table, Table II, poles, run maps.
'use strict';

const kPaperFilters = ['cas', 'wiener', 'average', 'median', 'cwm'];
// Filters of bench.json in the paper's order, then any further pipelines by name.
let kFilters = kPaperFilters.slice();
cm.benchFilters = (runs) => {
  const names = new Set(runs.flatMap((r) => Object.keys(r.filters || {})));
  return [...kPaperFilters.filter((f) => names.has(f)),
    ...[...names].filter((f) => !kPaperFilters.includes(f)).sort()];
};
const kFilterLabels = { cas: 'CAS', wiener: 'Wiener', average: 'Averaging', median: 'Median', cwm: 'CWM' };

// As pipeline::BenchRunName: courseNN_TEST, or <scene stem>_<motion> for --scenes runs
// (<folder>_scene for a dataset sample's NNNNNN/scene.yaml).
cm.runName = (run) => {
  if (!run.scene) return `course${String(run.course).padStart(2, '0')}_${run.test}`;
  const parts = run.scene.split('/');
  let stem = parts[parts.length - 1].replace(/\.[^.]*$/, '');
  if (stem === 'scene' && parts.length > 1) stem = parts[parts.length - 2] + '_' + stem;
  return `${stem}_${run.test}`;
};

// The filter with the lowest PI in a run (Eq. 11: lower is better).
cm.bestFilter = (run) => {
  let best = null;
  for (const f of kFilters) {
    const pi = run.filters?.[f]?.pi;
    if (typeof pi === 'number' && (best === null || pi < run.filters[best].pi)) best = f;
  }
  return best;
};

// Loads a run's interactive maps (runs/<name>/maps.json, written by casmap bench --maps).
cm.loadMapSet = async (dir) => {
  const set = await cm.json(cm.files(dir + '/maps.json'));
  const layers = await Promise.all(set.layers.map(async (l) => ({
    name: l.name,
    label: l.label || l.name,
    kind: l.kind || cm.layerKind(l.name),
    unit: l.unit ?? (cm.layerKind(l.name) === 'elevation' ? 'm' : ''),
    map: await cm.map('/api/map?' + cm.q({ path: dir + '/' + l.file })),
  })));
  return { grid: set.grid, layers };
};

cm.showBench = async (main) => {
  const bench = await cm.json('/files/bench.json');
  const runs = bench.runs || [];
  kFilters = cm.benchFilters(runs);

  const chart = cm.section('PI per course and filter (Fig. 8)', 'chart');
  if (await cm.exists('/files/pi_chart.png')) {
    chart.append(cm.el('img', { class: 'chart', src: '/files/pi_chart.png', alt: 'PI chart' }));
  } else {
    chart.append(cm.el('p', { class: 'hint' }, 'pi_chart.png not in this folder'));
  }

  const piSection = cm.section('Performance index (Eq. 11; lower is better; ★ best per run)', 'pi');
  const columns = [
    { key: 'course', label: 'course', value: (r) => r.course },
    { key: 'test', label: 'test', text: true, value: (r) => r.test },
    { key: 'scans', label: 'scans', value: (r) => r.scans },
    ...kFilters.map((f) => ({
      key: f, label: 'PI ' + (kFilterLabels[f] ?? f), digits: 4,
      value: (r) => r.filters?.[f]?.pi ?? null,
      cls: (r) => (cm.bestFilter(r) === f ? 'best' : ''),
    })),
    { key: 'best', label: 'best', text: true, value: (r) => kFilterLabels[cm.bestFilter(r)] ?? cm.bestFilter(r) ?? '–' },
    { key: 'raw_spikes', label: 'raw spikes', value: (r) => r.raw?.spikes ?? null },
    { key: 'cas_spikes', label: 'CAS spikes', value: (r) => r.filters?.cas?.spikes ?? null },
    { key: 'raw_rmse', label: 'raw RMSE m', digits: 4, value: (r) => r.raw?.rmse_m ?? null },
    { key: 'cas_rmse', label: 'CAS RMSE m', digits: 4, value: (r) => r.filters?.cas?.rmse_m ?? null },
  ];
  const rows = runs.map((r) => ({ ...r, __key: cm.runName(r) }));
  const mapsSection = cm.el('section', { id: 'maps' }, cm.el('h2', {}, 'Run maps'));
  const select = cm.el('select', { id: 'run-select' },
    rows.map((r) => cm.el('option', { value: r.__key }, r.__key)));
  piSection.append(cm.el('div', { class: 'scroll' }, cm.table(columns, rows, {
    id: 'pi-table',
    onRow: (r) => { select.value = r.__key; showRun(r.__key); mapsSection.scrollIntoView(); },
  })));

  for (const [file, title, id] of [['table2.md', 'Table II: CAS pixel classes', 'table2'],
    ['poles.md', 'Poles kept', 'poles'],
    ['pipelines.md', 'Named pipelines side by side', 'pipelines']]) {
    const s = cm.section(title, id);
    try {
      s.append(cm.markdown(await cm.text(cm.files(file))));
    } catch (e) {
      s.append(cm.el('p', { class: 'hint' }, file + ' not in this folder'));
    }
  }

  main.append(mapsSection);
  const body = cm.el('div', { id: 'run-maps' });
  mapsSection.append(cm.el('div', { class: 'toolbar' }, 'run ', select), body);
  async function showRun(name) {
    body.replaceChildren(cm.el('p', { class: 'hint' }, 'loading ' + name + '…'));
    try {
      if (await cm.exists(cm.files(`runs/${name}/maps.json`))) {
        const set = await cm.loadMapSet(`runs/${name}`);
        cm.mapViewer(body, set.layers, set.grid);
        return;
      }
      body.replaceChildren(cm.el('p', { class: 'hint' },
        'No interactive maps for this run (run casmap bench with --maps); the Fig. 7 sheet:'));
      if (await cm.exists(cm.files(`sheets/${name}.png`))) {
        body.append(cm.el('img', { class: 'chart', src: cm.files(`sheets/${name}.png`) }));
      }
    } catch (e) {
      cm.error(body, e);
    }
  }
  select.addEventListener('change', () => showRun(select.value));
  if (rows.length > 0) await showRun(rows[0].__key);
};
