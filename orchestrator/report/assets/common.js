// Helpers both reports share: building elements, numbers, verdict colours, tables.
'use strict';
const REPORT = JSON.parse(document.getElementById('report-data').textContent);

const VERDICT_COLORS = { success: '#2e9d46', failure: '#d62f2f', error: '#8a4fd0', missing: '#98a1ab' };

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === undefined || v === null) continue;
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children.flat()) if (c !== null && c !== undefined) e.append(c instanceof Node ? c : String(c));
  return e;
}

const SVG_NS = 'http://www.w3.org/2000/svg';
function svgEl(tag, attrs) {
  const e = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs || {})) if (v !== undefined && v !== null) e.setAttribute(k, v);
  return e;
}

// Decimals that tell apart values `step` apart (at least two, at most six): a metric that
// spans 0.005 s gets 1.9793 … 1.9796, not 1.98 … 1.98.
function digitsFor(step) {
  return step > 0 ? Math.min(6, Math.max(2, Math.ceil(-Math.log10(step)) + 1)) : 2;
}

function fmtNum(v, digits) {
  if (v === null || v === undefined || Number.isNaN(v)) return '–';
  if (typeof v !== 'number') return String(v);
  return v.toFixed(digits === undefined ? 2 : digits);
}

function verdictBadge(v) { return el('span', { class: 'verdict v-' + v, text: v }); }

function card(title, ...children) { return el('section', { class: 'card' }, title ? el('h2', { text: title }) : null, ...children); }

// A table whose columns sort on a click of their header. `columns`: [{label, value(row), render(row)?, num?}].
function sortableTable(columns, rows, attrs) {
  const table = el('table', attrs || {});
  const tbody = el('tbody');
  let sortBy = -1, ascending = true;
  const head = el('tr', {}, columns.map((c, i) => el('th', { class: 'sortable', onclick: () => {
    ascending = sortBy === i ? !ascending : true;
    sortBy = i;
    fill();
  } }, c.label)));
  table.append(el('thead', {}, head), tbody);
  let shown = rows;
  function fill() {
    const list = shown.slice();
    if (sortBy >= 0) {
      const c = columns[sortBy];
      list.sort((a, b) => {
        const x = c.value(a), y = c.value(b);
        const r = typeof x === 'number' && typeof y === 'number' ? x - y : String(x).localeCompare(String(y));
        return ascending ? r : -r;
      });
    }
    tbody.replaceChildren(...list.map(r => el('tr', {}, columns.map(c =>
      el('td', { class: c.num ? 'num' : c.cls }, c.render ? c.render(r) : fmtCell(c.value(r)))))));
  }
  table.show = (subset) => { shown = subset; fill(); };
  fill();
  return table;
}

function fmtCell(v) { return typeof v === 'number' ? (Number.isInteger(v) ? String(v) : fmtNum(v, Math.abs(v) >= 100 ? 1 : 3)) : (v === null || v === undefined ? '–' : String(v)); }

// Chart.js defaults: a report is read, not animated.
Chart.defaults.animation = false;
Chart.defaults.font.size = 11;
Chart.defaults.maintainAspectRatio = false;
Chart.defaults.plugins.legend.labels.boxWidth = 12;

// Reports report their own script errors in the page too, not only in the console.
window.addEventListener('error', (e) => {
  const app = document.getElementById('app');
  if (app) app.prepend(el('div', { class: 'problem', text: 'report script error: ' + e.message }));
});
