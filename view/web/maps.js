// Map panels side by side: one colour scale for every elevation layer, zoom, scroll kept in
// step, the cell under the pointer highlighted in every panel and its values listed.
'use strict';

// CAS classes (mapper::PixelClass): untouched, removed (mixed/artifact), filled (missing), border.
const kClassNames = ['untouched', 'removed', 'filled', 'border'];
const kClassColours = [[200, 200, 200], [220, 40, 40], [40, 90, 220], [90, 90, 90]];
const kZooms = [1, 2, 3, 4, 6, 8, 12, 16, 24];

// layers: [{name, label, map: {rows, cols, data}, kind: 'elevation'|'certainty'|'classes'|
// 'other', unit}]; grid: {x0_m, y0_m, cell_m} or null. Returns {setCell(row, col)}.
cm.mapViewer = (container, layers, grid, { infoId = 'cell-info' } = {}) => {
  container.replaceChildren();
  if (layers.length === 0) return null;
  const rows = layers[0].map.rows;
  const cols = layers[0].map.cols;
  const scaleOfOne = (l) => {
    let lo = Infinity;
    let hi = -Infinity;
    for (const v of l.map.data) if (Number.isFinite(v)) { if (v < lo) lo = v; if (v > hi) hi = v; }
    return Number.isFinite(lo) ? [lo, hi > lo ? hi : lo + 1e-6] : [0, 1];
  };
  // One scale for every elevation panel: the truth's range when there is a truth layer (so
  // spikes and holes saturate instead of flattening the terrain), else the 1st-99th percentile.
  const truth = layers.find((l) => l.kind === 'elevation' && /truth/.test(l.name));
  const percentiles = (kinds) => {
    const v = layers.filter((l) => kinds.includes(l.kind))
      .flatMap((l) => Array.from(l.map.data).filter(Number.isFinite)).sort((a, b) => a - b);
    if (v.length === 0) return [0, 1];
    const lo = v[Math.floor(0.01 * (v.length - 1))];
    const hi = v[Math.ceil(0.99 * (v.length - 1))];
    return [lo, hi > lo ? hi : lo + 1e-6];
  };
  const shared = truth ? scaleOfOne(truth) : percentiles(['elevation']);
  const colourer = (l) => {
    if (l.kind === 'classes') {
      return (v) => (Number.isFinite(v) && kClassColours[v]) || [255, 0, 255];
    }
    const [lo, hi] = l.kind === 'elevation' ? shared : scaleOfOne(l);
    return (v) => (Number.isFinite(v) ? cm.viridis((v - lo) / (hi - lo)) : [255, 0, 255]);
  };

  let zoom = kZooms.filter((z) => z * cols <= 240).pop() || 1;
  let cell = null;
  let pinned = false;
  let syncing = false;

  const zoomLabel = cm.el('span', { id: 'zoom-label' });
  const legend = cm.el('canvas', { width: 160, height: 12 });
  const lctx = legend.getContext('2d');
  for (let x = 0; x < 160; x++) {
    const [r, g, b] = cm.viridis(x / 159);
    lctx.fillStyle = `rgb(${r},${g},${b})`;
    lctx.fillRect(x, 0, 1, 12);
  }
  const setZoom = (z) => { zoom = z; draw(); };
  const step = (d) => {
    const i = kZooms.indexOf(zoom) + d;
    if (i >= 0 && i < kZooms.length && kZooms[i] * Math.max(rows, cols) <= 16384) setZoom(kZooms[i]);
  };
  container.append(cm.el('div', { class: 'toolbar' },
    cm.el('button', { onclick: () => step(-1), id: 'zoom-out' }, '−'),
    cm.el('button', { onclick: () => step(1), id: 'zoom-in' }, '+'), zoomLabel,
    cm.el('span', { class: 'legend' }, `elevation ${cm.fmt(shared[0], 3)} m`, legend,
      `${cm.fmt(shared[1], 3)} m (one scale for every elevation panel` + (truth ? ': the truth\'s range, beyond it saturated' : ': 1st-99th percentile') + '; magenta: NaN)')));
  const info = cm.el('div', { id: infoId, class: 'cell-info' },
    cm.el('span', { class: 'hint' }, 'point at a cell (click pins it)'));
  container.append(info);
  const panels = cm.el('div', { class: 'panels' });
  container.append(panels);

  const views = layers.map((l) => {
    const off = cm.el('canvas', { width: cols, height: rows });
    const octx = off.getContext('2d');
    const img = octx.createImageData(cols, rows);
    const colour = colourer(l);
    for (let i = 0; i < rows * cols; i++) {
      const [r, g, b] = colour(l.map.data[i]);
      img.data[4 * i] = r; img.data[4 * i + 1] = g; img.data[4 * i + 2] = b; img.data[4 * i + 3] = 255;
    }
    octx.putImageData(img, 0, 0);
    const canvas = cm.el('canvas', { dataset: { layer: l.name } });
    const frame = cm.el('div', { class: 'frame' }, canvas);
    panels.append(cm.el('div', { class: 'panel' }, cm.el('span', { class: 'name' }, l.label), frame));
    const pick = (e) => {
      const c = Math.floor(e.offsetX / zoom);
      const r = Math.floor(e.offsetY / zoom);
      return r >= 0 && r < rows && c >= 0 && c < cols ? [r, c] : null;
    };
    canvas.addEventListener('mousemove', (e) => { if (!pinned) setCell(pick(e)); });
    canvas.addEventListener('click', (e) => { pinned = !pinned; setCell(pick(e)); });
    canvas.addEventListener('wheel', (e) => {
      if (!e.ctrlKey) return;
      e.preventDefault();
      step(e.deltaY < 0 ? 1 : -1);
    });
    frame.addEventListener('scroll', () => {
      if (syncing) return;
      syncing = true;
      for (const v of views) if (v.frame !== frame) { v.frame.scrollTop = frame.scrollTop; v.frame.scrollLeft = frame.scrollLeft; }
      syncing = false;
    });
    return { layer: l, off, canvas, frame };
  });

  const drawOne = (v) => {
    const ctx = v.canvas.getContext('2d');
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(v.off, 0, 0, cols * zoom, rows * zoom);
    if (cell) {
      const [r, c] = cell;
      ctx.lineWidth = 2;
      ctx.strokeStyle = '#ff2020';
      ctx.strokeRect(c * zoom - 1, r * zoom - 1, zoom + 2, zoom + 2);
      ctx.strokeStyle = '#ffffff';
      ctx.strokeRect(c * zoom - 3, r * zoom - 3, zoom + 6, zoom + 6);
    }
  };
  function draw() {
    for (const v of views) {
      v.canvas.width = cols * zoom;
      v.canvas.height = rows * zoom;
      drawOne(v);
    }
    zoomLabel.textContent = `${zoom} px/cell, ${rows} × ${cols} cells`;
    zoomLabel.dataset.zoom = String(zoom);
  }
  function setCell(rc) {
    cell = rc;
    views.forEach(drawOne);
    if (!rc) return;
    const [r, c] = rc;
    const parts = [cm.el('span', { dataset: { field: 'row', value: r } }, cm.el('b', {}, 'row '), r),
      cm.el('span', { dataset: { field: 'col', value: c } }, cm.el('b', {}, 'col '), c)];
    if (grid) {
      // Cell centre (DESIGN.md map grid: row along world x, col along world y).
      const x = grid.x0_m + (r + 0.5) * grid.cell_m;
      const y = grid.y0_m + (c + 0.5) * grid.cell_m;
      parts.push(cm.el('span', { dataset: { field: 'x', value: x } }, cm.el('b', {}, 'x '), x.toFixed(4), ' m'),
        cm.el('span', { dataset: { field: 'y', value: y } }, cm.el('b', {}, 'y '), y.toFixed(4), ' m'));
    }
    for (const l of layers) {
      const v = l.map.data[r * cols + c];
      const shown = l.kind === 'classes' ? (kClassNames[v] ?? String(v))
        : Number.isFinite(v) ? v.toFixed(4) + (l.unit ? ' ' + l.unit : '') : 'NaN';
      parts.push(cm.el('span', { dataset: { layer: l.name, value: String(v) } },
        cm.el('b', {}, l.label + ' '), shown));
    }
    info.replaceChildren(...parts);
  }
  draw();
  return { setCell, views, zoom: () => zoom };
};

// Layer kind and label from a layer name (bench maps.json, run file /maps names, TIFF names).
cm.layerKind = (name) => {
  if (/class/.test(name)) return 'classes';
  if (/certainty/.test(name)) return 'certainty';
  return 'elevation';
};
