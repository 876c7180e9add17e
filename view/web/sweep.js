// Sweep folder (casmap sweep --out DIR): heat map of CAS's mean PI over two parameters with the
// Pareto points (PI, poles kept, spikes), a table of every point, details on click.
'use strict';

// Objectives of a point: PI (min), then poles kept (max) and spikes (min) when reported.
const sweepObjectives = (points) => {
  const keys = Object.keys(points[0] || {});
  const poles = keys.find((k) => /poles/.test(k) && typeof points[0][k] === 'number');
  const spikes = keys.find((k) => /spike/.test(k) && typeof points[0][k] === 'number');
  const obj = [(p) => p.pi_mean];
  if (poles) obj.push((p) => -p[poles]);
  if (spikes) obj.push((p) => p[spikes]);
  return obj;
};

// Indices on the Pareto front: from sweep.json when it gives them, else computed here.
cm.paretoIndices = (sweep) => {
  const points = sweep.points || [];
  const given = sweep.pareto_front ?? sweep.pareto;
  if (Array.isArray(given)) {
    return new Set(given.map((g) => (typeof g === 'number' ? g : g.index ?? points.indexOf(g))));
  }
  if (points.some((p) => typeof p.pareto === 'boolean')) {
    return new Set(points.flatMap((p, i) => (p.pareto ? [i] : [])));
  }
  const obj = sweepObjectives(points);
  const vals = points.map((p) => obj.map((f) => f(p)));
  const front = new Set();
  vals.forEach((v, i) => {
    if (!v.every(Number.isFinite)) return;
    const dominated = vals.some((w, j) => j !== i && w.every(Number.isFinite) &&
      w.every((x, k) => x <= v[k]) && w.some((x, k) => x < v[k]));
    if (!dominated) front.add(i);
  });
  return front;
};

cm.showSweep = async (main) => {
  const sweep = await cm.json('/files/sweep.json');
  const points = sweep.points || [];
  const params = sweep.parameters || [];
  const pareto = cm.paretoIndices(sweep);
  const details = cm.el('div', { id: 'point-details' },
    cm.el('p', { class: 'hint' }, 'click a point for its parameters'));
  const show = (i) => {
    const p = points[i];
    const rows = Object.entries(p.params || {}).map(([k, v]) => cm.el('tr', {},
      cm.el('th', {}, k), cm.el('td', { dataset: { param: k } }, cm.fmt(v))));
    for (const [k, v] of Object.entries(p)) {
      if (k !== 'params') rows.push(cm.el('tr', {}, cm.el('th', {}, k), cm.el('td', {}, cm.fmt(v))));
    }
    details.replaceChildren(cm.el('h3', {}, `point ${i}` + (pareto.has(i) ? ' (Pareto front)' : '') +
      (i === sweep.best_point ? ' (lowest mean PI)' : '')), cm.el('table', {}, rows));
  };

  const head = cm.section('Sweep', 'sweep');
  head.append(cm.el('p', {}, `parameters: ${params.join(', ') || '–'}; fixed: ${(sweep.fixed || []).join(', ') || '–'}; ` +
    `courses: ${(sweep.courses || []).join(', ')}; tests: ${(sweep.tests || []).join(', ')}; ` +
    `${points.length} points; ${pareto.size} on the Pareto front (` +
    sweepObjectives(points).length + ' objectives).'));

  if (params.length === 2 && points.length > 0) {
    const heat = cm.section('Mean PI of CAS (lower is better); ○ Pareto front, ★ lowest PI', 'heat');
    const xs = [...new Set(points.map((p) => p.params[params[0]]))].sort((a, b) => a - b);
    const ys = [...new Set(points.map((p) => p.params[params[1]]))].sort((a, b) => a - b);
    const cw = Math.max(36, Math.min(80, Math.floor(640 / xs.length)));
    const ch = Math.max(24, Math.min(48, Math.floor(400 / ys.length)));
    const left = 70;
    const top = 10;
    const canvas = cm.el('canvas', { id: 'heat-canvas', class: 'heat',
      width: left + cw * xs.length + 10, height: top + ch * ys.length + 40 });
    const ctx = canvas.getContext('2d');
    const finite = points.map((p) => p.pi_mean).filter(Number.isFinite);
    const lo = Math.min(...finite);
    const hi = Math.max(...finite);
    const cellOf = (p) => [xs.indexOf(p.params[params[0]]), ys.length - 1 - ys.indexOf(p.params[params[1]])];
    ctx.font = '11px sans-serif';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    points.forEach((p, i) => {
      const [cx, cy] = cellOf(p);
      const [r, g, b] = Number.isFinite(p.pi_mean) ? cm.viridis((p.pi_mean - lo) / ((hi - lo) || 1)) : [150, 150, 150];
      ctx.fillStyle = `rgb(${r},${g},${b})`;
      ctx.fillRect(left + cx * cw, top + cy * ch, cw - 1, ch - 1);
      ctx.fillStyle = (r + g + b) / 3 > 128 ? '#000' : '#fff';
      ctx.fillText(cm.fmt(p.pi_mean, 3) + (i === sweep.best_point ? '★' : ''), left + (cx + 0.5) * cw, top + (cy + 0.5) * ch);
      if (pareto.has(i)) {
        ctx.strokeStyle = '#ff3030';
        ctx.lineWidth = 2;
        ctx.beginPath();
        ctx.arc(left + (cx + 0.5) * cw, top + (cy + 0.5) * ch, Math.min(cw, ch) / 2 - 2, 0, 2 * Math.PI);
        ctx.stroke();
      }
    });
    ctx.fillStyle = '#000';
    xs.forEach((x, i) => ctx.fillText(cm.fmt(x, 3), left + (i + 0.5) * cw, top + ys.length * ch + 10));
    ctx.textAlign = 'right';
    ys.forEach((y, i) => ctx.fillText(cm.fmt(y, 3), left - 4, top + (ys.length - 1 - i + 0.5) * ch));
    ctx.textAlign = 'center';
    ctx.fillText(params[0], left + (xs.length * cw) / 2, top + ys.length * ch + 28);
    ctx.save();
    ctx.translate(12, top + (ys.length * ch) / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.fillText(params[1], 0, 0);
    ctx.restore();
    canvas.addEventListener('click', (e) => {
      const cx = Math.floor((e.offsetX - left) / cw);
      const cy = Math.floor((e.offsetY - top) / ch);
      const i = points.findIndex((p) => { const [a, b] = cellOf(p); return a === cx && b === cy; });
      if (i >= 0) show(i);
    });
    heat.append(canvas);
  }

  const table = cm.section('Points', 'points');
  const extra = Object.keys(points[0] || {}).filter((k) => k !== 'params' &&
    typeof points[0][k] === 'number');
  const columns = [
    { key: 'index', label: '#', value: (p) => p.__index },
    ...params.map((k) => ({ key: 'p_' + k, label: k, value: (p) => p.params?.[k] ?? null })),
    ...extra.map((k) => ({ key: k, label: k, value: (p) => p[k], digits: 4 })),
    { key: 'pareto', label: 'Pareto', text: true, value: (p) => (pareto.has(p.__index) ? 'yes' : '') },
  ];
  table.append(cm.el('div', { class: 'scroll' }, cm.table(columns,
    points.map((p, i) => ({ ...p, __index: i, __key: String(i) })),
    { id: 'points-table', onRow: (p) => show(p.__index) })));
  const det = cm.section('Point', 'point');
  det.append(details);
  if (await cm.exists('/files/heatmap.png')) {
    cm.section('heatmap.png (as written by casmap sweep)', 'heatpng')
      .append(cm.el('img', { class: 'chart', src: '/files/heatmap.png' }));
  }
  main.append();
};
