// Shared helpers of the casmap view page: fetching, DOM building, tables, Markdown, colours.
'use strict';

const cm = {};

cm.get = async (url) => {
  const r = await fetch(url, { cache: 'no-store' });
  if (!r.ok) throw new Error(url + ': ' + r.status + ' ' + (await r.text()).trim());
  return r;
};
cm.json = async (url) => (await cm.get(url)).json();
cm.text = async (url) => (await cm.get(url)).text();
cm.exists = async (url) => {
  const r = await fetch(url, { method: 'HEAD', cache: 'no-store' });
  return r.ok;
};
cm.q = (params) => new URLSearchParams(params).toString();
cm.files = (path) => '/files/' + path.split('/').map(encodeURIComponent).join('/');

// A float map from /api/map or /api/runmap: "CMF1", rows, cols (uint32 LE), float32 LE values.
cm.map = async (url) => {
  const buf = await (await cm.get(url)).arrayBuffer();
  const view = new DataView(buf);
  const magic = String.fromCharCode(...new Uint8Array(buf, 0, 4));
  if (magic !== 'CMF1') throw new Error(url + ': not a CMF1 map');
  const rows = view.getUint32(4, true);
  const cols = view.getUint32(8, true);
  return { rows, cols, data: new Float32Array(buf.slice(12)) };
};

// el('td', {class: 'x', dataset: {a: 1}}, 'text', child, ...)
cm.el = (tag, attrs, ...children) => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'dataset') Object.assign(e.dataset, v);
    else if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children.flat()) {
    if (c === null || c === undefined) continue;
    e.append(c instanceof Node ? c : document.createTextNode(String(c)));
  }
  return e;
};
cm.section = (title, id) => {
  const s = cm.el('section', { id }, cm.el('h2', {}, title));
  document.getElementById('main').append(s);
  return s;
};

cm.fmt = (v, digits = 4) => {
  if (v === null || v === undefined) return '–';
  if (typeof v === 'number') {
    if (!Number.isFinite(v)) return '–';
    return Number.isInteger(v) ? String(v) : v.toFixed(digits);
  }
  if (typeof v === 'object') return JSON.stringify(v);
  return String(v);
};

// A table sortable by any column. columns: [{key, label, text?, value(row), digits?,
// cls(row)?}]; rows: plain objects. onRow(row, tr) is called on click.
cm.table = (columns, rows, { id, onRow } = {}) => {
  const table = cm.el('table', { id });
  const head = cm.el('tr', {});
  const body = cm.el('tbody', {});
  let sortKey = null;
  let asc = true;
  const render = () => {
    const sorted = rows.slice();
    if (sortKey !== null) {
      const col = columns.find((c) => c.key === sortKey);
      sorted.sort((a, b) => {
        const x = col.value(a);
        const y = col.value(b);
        const nx = x === null || x === undefined || (typeof x === 'number' && !isFinite(x));
        const ny = y === null || y === undefined || (typeof y === 'number' && !isFinite(y));
        if (nx || ny) return nx === ny ? 0 : nx ? 1 : -1;  // blanks last
        const d = typeof x === 'number' && typeof y === 'number' ? x - y
          : String(x).localeCompare(String(y), undefined, { numeric: true });
        return asc ? d : -d;
      });
    }
    body.replaceChildren(...sorted.map((row) => {
      const tr = cm.el('tr', { dataset: { key: row.__key ?? '' } }, columns.map((c) => {
        const v = c.value(row);
        const cls = [c.text ? 'text' : '', c.cls ? c.cls(row) : ''].join(' ').trim();
        const attrs = { class: cls, dataset: { col: c.key } };
        if (typeof v === 'number' && Number.isFinite(v)) attrs.dataset.value = String(v);
        return cm.el('td', attrs, cm.fmt(v, c.digits));
      }));
      if (onRow) {
        tr.addEventListener('click', () => {
          body.querySelectorAll('tr.selected').forEach((t) => t.classList.remove('selected'));
          tr.classList.add('selected');
          onRow(row, tr);
        });
      }
      return tr;
    }));
    head.querySelectorAll('th').forEach((th) => {
      th.classList.toggle('sorted-asc', th.dataset.col === sortKey && asc);
      th.classList.toggle('sorted-desc', th.dataset.col === sortKey && !asc);
    });
  };
  for (const c of columns) {
    head.append(cm.el('th', {
      dataset: { col: c.key },
      onclick: () => { asc = sortKey === c.key ? !asc : true; sortKey = c.key; render(); },
    }, c.label));
  }
  table.append(cm.el('thead', {}, head), body);
  render();
  table.setRows = (r) => { rows = r; render(); };
  return table;
};

// Markdown subset the reports use: headings, pipe tables, lists, paragraphs, `code`.
cm.markdown = (text) => {
  const out = cm.el('div', { class: 'md' });
  const lines = text.split('\n');
  const inline = (s) => s.replace(/\*\*|`/g, '');
  for (let i = 0; i < lines.length;) {
    const line = lines[i];
    if (/^\s*\|/.test(line)) {
      const rows = [];
      while (i < lines.length && /^\s*\|/.test(lines[i])) rows.push(lines[i++]);
      const cells = (l) => l.trim().replace(/^\||\|$/g, '').split('|').map((c) => inline(c.trim()));
      const table = cm.el('table', {});
      rows.forEach((r, k) => {
        if (k === 1 && /^[\s|:-]+$/.test(r)) return;
        table.append(cm.el('tr', {}, cells(r).map((c) => cm.el(k === 0 ? 'th' : 'td',
          { class: /^[-+]?[\d.]+%?$/.test(c) ? '' : 'text' }, c))));
      });
      out.append(table);
      continue;
    }
    const h = /^(#{1,6})\s+(.*)$/.exec(line);
    if (h) out.append(cm.el('h' + Math.min(6, h[1].length + 1), {}, inline(h[2])));
    else if (/^\s*[-*]\s+/.test(line)) out.append(cm.el('li', {}, inline(line.replace(/^\s*[-*]\s+/, ''))));
    else if (line.trim() !== '') out.append(cm.el('p', {}, inline(line)));
    i++;
  }
  return out;
};

// Viridis (matplotlib), 9 stops, linearly interpolated.
const kViridis = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
  [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
cm.viridis = (u) => {
  const t = Math.min(1, Math.max(0, u)) * (kViridis.length - 1);
  const i = Math.min(kViridis.length - 2, Math.floor(t));
  const f = t - i;
  const a = kViridis[i];
  const b = kViridis[i + 1];
  return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
};

cm.error = (where, e) => {
  where.append(cm.el('p', { class: 'error' }, String(e.message || e)));
};
