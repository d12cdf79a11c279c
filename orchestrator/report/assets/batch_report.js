// report.html of a batch: counts, parameter space per logical scenario, scene graphs, runs.
'use strict';
(function () {
  const B = REPORT;
  const app = document.getElementById('app');
  const runs = B.runs || [];
  const VERDICTS = ['success', 'failure', 'error'];

  // ------------------------------------------------------------------ header
  function header() {
    const t = B.totals || {};
    const c = card(null, el('h1', { text: 'Batch report' }),
      el('div', { class: 'muted', text: `${t.runs} runs · ${(B.logical_scenarios || []).length} logical scenario(s)` +
        (B.wall_time_s ? ` · ${fmtNum(B.wall_time_s, 1)} s wall` : '') + (B.shards && B.shards.length ? ' · shards ' + B.shards.join(', ') : '') }));
    c.append(el('div', { class: 'counts', id: 'counts' }, ['success', 'failure', 'error', 'missing'].map(v =>
      el('div', { class: 'count v-' + v, 'data-verdict': v }, el('b', { text: String(t[v] || 0) }), v))));
    return c;
  }

  // ------------------------------------------------------------------ parameter space
  const numeric = (v) => typeof v === 'number' || typeof v === 'boolean';
  // A metric value of a run by name ("" = none chosen).
  const metricOf = (r, name) => (name && r.metrics && typeof r.metrics[name] === 'number' ? r.metrics[name] : null);
  // Blue (low) to red (high): a minimum TTC that is small shows red.
  function rampColor(v, lo, hi, invert) {
    let f = hi > lo ? (v - lo) / (hi - lo) : 0.5;
    if (invert) f = 1 - f;
    const r = Math.round(40 + 200 * f), g = Math.round(110 + 40 * (1 - Math.abs(f - 0.5) * 2)), b = Math.round(220 - 190 * f);
    return `rgb(${r},${g},${b})`;
  }

  function scenarioSection(s) {
    const mine = runs.filter(r => r.logical_uuid === s.logical_uuid);
    const c = card(s.name || s.logical_uuid);
    c.append(el('div', { class: 'muted' }, `${mine.length} run(s) finished: `,
      VERDICTS.map(v => el('span', {}, verdictBadge(v), ` ${mine.filter(r => r.verdict === v).length}  `))));
    // Parameters that vary and are numbers: the axes of the parameter space.
    const params = (s.parameters || []).filter(p => {
      const vals = new Set(mine.map(r => r.values[p]).filter(numeric));
      return vals.size > 1;
    });
    // A summary's `partner` is an actor id, not a measure: nothing to colour by.
    const metricNames = [...new Set(mine.flatMap(r => Object.keys(r.metrics || {})
      .filter(k => typeof r.metrics[k] === 'number' && !k.endsWith('.partner'))))].sort();
    // Colour by default by a measure that tells the runs apart: the minimum TTC, whether a
    // collision was preventable, any other; one that is the same in every run colours nothing.
    const varies = n => new Set(mine.map(r => metricOf(r, n)).filter(v => v !== null)).size > 1;
    const preferred = metricNames.filter(varies).find(n => /min_?ttc(\.value)?$/i.test(n)) ||
      metricNames.filter(varies).find(n => /preventable/i.test(n)) || metricNames.find(varies) || '';
    const select = el('select', { class: 'color-by' }, el('option', { value: '', text: 'verdict' }),
      metricNames.map(n => el('option', { value: n, text: n, selected: n === preferred ? '' : null })));
    const grid = el('div', { class: 'scatter-grid' });
    const hist = el('div', {});
    c.append(el('h3', { text: 'Parameter space: every run, one point each' }));
    if (metricNames.length) c.append(el('div', { class: 'controls' }, 'colour by ', select));
    c.append(grid, hist);
    const charts = [];
    const pairs = [];
    for (let i = 0; i < params.length; i++) for (let j = i + 1; j < params.length; j++) pairs.push([params[i], params[j]]);
    if (params.length === 1) pairs.push([params[0], 'seed']);
    if (!pairs.length) grid.append(el('div', { class: 'muted', text: 'No parameter varies between the runs: nothing to plot.' }));
    const valueOf = (r, p) => (p === 'seed' ? r.seed : Number(r.values[p]));
    function draw() {
      charts.forEach(ch => ch.destroy());
      charts.length = 0;
      grid.replaceChildren();
      const metric = select.value;
      const values = mine.map(r => metricOf(r, metric)).filter(v => v !== null);
      const lo = Math.min(...values), hi = Math.max(...values);
      const invert = /ttc|thw|gap|dist/i.test(metric);
      for (const [px, py] of pairs) {
        const datasets = metric
          ? [{ label: metric, data: mine.map(r => ({ x: valueOf(r, px), y: valueOf(r, py), run: r })),
               pointBackgroundColor: mine.map(r => (metricOf(r, metric) === null ? '#ccc' : rampColor(metricOf(r, metric), lo, hi, invert))),
               pointBorderColor: mine.map(r => VERDICT_COLORS[r.verdict] || '#999'), pointBorderWidth: 1.5, pointRadius: 4.5 }]
          : VERDICTS.map(v => ({ label: v, backgroundColor: VERDICT_COLORS[v], borderColor: VERDICT_COLORS[v], pointRadius: 4,
               data: mine.filter(r => r.verdict === v).map(r => ({ x: valueOf(r, px), y: valueOf(r, py), run: r })) }));
        const canvas = el('canvas', { class: 'scatter', 'data-x': px, 'data-y': py });
        grid.append(el('div', { class: 'scatter-box' }, canvas));
        charts.push(new Chart(canvas, {
          type: 'scatter', data: { datasets },
          // (parsed: Chart.js takes unparsed data to be sorted by x, which a parameter space is not)
          options: {
            scales: { x: { title: { display: true, text: px } }, y: { title: { display: true, text: py } } },
            plugins: { legend: { display: !metric },
              title: { display: !!metric, text: metric ? `colour: ${metric} (${fmtNum(lo, digitsFor(hi - lo))} … ${fmtNum(hi, digitsFor(hi - lo))}), border: verdict` : '' },
              tooltip: { callbacks: { label: (item) => {
                const r = item.raw.run;
                return `${r.verdict} · seed ${r.seed}${metric ? ` · ${metric} ${fmtNum(metricOf(r, metric), 3)}` : ''} · ${r.values_text}`;
              } } } },
            onClick: (e, items) => { if (items.length) { const r = items[0].element.$context.raw.run; if (r.report) window.open(r.report); } } },
        }));
      }
      hist.replaceChildren();
      if (metric && values.length) hist.append(histogram(mine, metric, lo, hi));
    }
    function histogram(list, metric, lo, hi) {
      const bins = 16, width = hi > lo ? (hi - lo) / bins : 1;
      const digits = digitsFor(width);
      const labels = [...Array(bins).keys()].map(i => fmtNum(lo + (i + 0.5) * width, digits));
      const datasets = VERDICTS.map(v => {
        const counts = new Array(bins).fill(0);
        for (const r of list) {
          const m = metricOf(r, metric);
          if (r.verdict !== v || m === null) continue;
          counts[Math.min(bins - 1, Math.floor((m - lo) / width))]++;
        }
        return { label: v, data: counts, backgroundColor: VERDICT_COLORS[v] };
      });
      const canvas = el('canvas', { class: 'histogram' });
      charts.push(new Chart(canvas, { type: 'bar', data: { labels, datasets },
        options: { scales: { x: { stacked: true, title: { display: true, text: metric } }, y: { stacked: true, title: { display: true, text: 'runs' }, ticks: { precision: 0 } } } } }));
      return el('div', {}, el('h3', { text: 'Histogram of ' + metric }), el('div', { class: 'chart-box' }, canvas));
    }
    select.addEventListener('change', draw);
    setTimeout(draw, 0);
    if (s.graph) c.append(el('h3', { text: 'Scene graph: how many runs took each transition and ended in each scene' }), sceneGraph(s.graph, mine));
    return c;
  }

  // ------------------------------------------------------------------ scene graph
  // Scenes in columns by their distance from the opening scene; edges labelled with the
  // number of runs that took them. Dashed: never taken in this batch.
  function sceneGraph(g, list) {
    const taken = new Map(), endedIn = new Map(), visited = new Map();
    for (const r of list) {
      const path = r.scenes || [];
      path.forEach((id, i) => {
        visited.set(id, (visited.get(id) || 0) + 1);
        if (i) { const k = path[i - 1] + '>' + id; taken.set(k, (taken.get(k) || 0) + 1); }
      });
      if (r.ending_scene !== null && r.ending_scene !== undefined) endedIn.set(r.ending_scene, (endedIn.get(r.ending_scene) || 0) + 1);
    }
    const depth = new Map([[0, 0]]), queue = [0];
    while (queue.length) {
      const n = queue.shift();
      for (const e of g.edges) if (e.from === n && !depth.has(e.to)) { depth.set(e.to, depth.get(n) + 1); queue.push(e.to); }
    }
    for (const n of g.nodes) if (!depth.has(n.id)) depth.set(n.id, 0);
    const columns = new Map();
    for (const n of g.nodes) { const d = depth.get(n.id); if (!columns.has(d)) columns.set(d, []); columns.get(d).push(n); }
    const W = 190, H = 64, GX = 70, GY = 26;
    const pos = new Map();
    let rowsMax = 0;
    for (const [d, ns] of columns) { ns.forEach((n, i) => pos.set(n.id, { x: 10 + d * (W + GX), y: 10 + i * (H + GY) })); rowsMax = Math.max(rowsMax, ns.length); }
    const width = 20 + columns.size * (W + GX) - GX, height = 20 + rowsMax * (H + GY) - GY;
    const svg = svgEl('svg', { class: 'graph', viewBox: `0 0 ${width} ${height}`, style: `max-width:${width}px` });
    const defs = svgEl('defs', {});
    const marker = svgEl('marker', { id: 'arrow', viewBox: '0 0 10 10', refX: 10, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse' });
    marker.append(svgEl('path', { d: 'M0,0 L10,5 L0,10 z', fill: '#5d6875' }));
    defs.append(marker);
    svg.append(defs);
    for (const e of g.edges) {
      const a = pos.get(e.from), b = pos.get(e.to);
      if (!a || !b) continue;
      const n = taken.get(e.from + '>' + e.to) || 0;
      const back = b.x <= a.x;
      const x1 = a.x + W, y1 = a.y + H / 2, x2 = back ? b.x + W / 2 : b.x, y2 = back ? b.y + (b.y > a.y ? 0 : H) : b.y + H / 2;
      const mx = (x1 + x2) / 2;
      const d = back ? `M${x1},${y1} C${x1 + 60},${y1} ${x2},${y2 + (b.y > a.y ? -50 : 50)} ${x2},${y2}` : `M${x1},${y1} C${mx},${y1} ${mx},${y2} ${x2},${y2}`;
      svg.append(svgEl('path', { class: 'edge' + (n ? '' : ' unused'), d, 'stroke-width': n ? 1.2 + Math.min(4, Math.log2(1 + n)) : 1.2, 'marker-end': 'url(#arrow)', 'data-runs': n }));
      const label = svgEl('text', { x: mx, y: (y1 + y2) / 2 - 4, 'text-anchor': 'middle' });
      label.textContent = String(n);
      svg.append(label);
    }
    for (const n of g.nodes) {
      const p = pos.get(n.id), v = visited.get(n.id) || 0, ended = endedIn.get(n.id) || 0;
      const node = svgEl('g', { class: 'node' + (n.ending ? ' ending' : '') + (v ? '' : ' unvisited'), 'data-scene': n.id, transform: `translate(${p.x},${p.y})` });
      node.append(svgEl('rect', { width: W, height: H, rx: 8 }));
      const t1 = svgEl('text', { x: 8, y: 17, 'font-weight': 600 });
      t1.textContent = (n.id === 0 ? 'opening ' : n.ending ? 'ending ' : 'scene ') + n.id + ` · ${v} run(s)`;
      const t2 = svgEl('text', { x: 8, y: 35 });
      const desc = n.description || '';
      t2.textContent = desc.length > 28 ? desc.slice(0, 27) + '…' : desc;
      const title = svgEl('title', {});
      title.textContent = desc;
      node.append(t1, t2, title);
      if (n.ending) { const t3 = svgEl('text', { x: 8, y: 53, fill: '#2e9d46' }); t3.textContent = `ended here: ${ended}`; node.append(t3); }
      svg.append(node);
    }
    return svg;
  }

  // ------------------------------------------------------------------ runs table
  function runsTable() {
    const c = card('Runs');
    const names = new Map((B.logical_scenarios || []).map(s => [s.logical_uuid, s.name || s.logical_uuid]));
    const verdictSel = el('select', { id: 'verdict-filter' }, el('option', { value: '', text: 'all verdicts' }), VERDICTS.map(v => el('option', { value: v, text: v })));
    const search = el('input', { type: 'search', id: 'run-search', placeholder: 'filter by text (values, reason, seed)…' });
    // Runs with a reference run (--reference-run) say whether their collision was preventable.
    const withReference = runs.some(r => r.preventable);
    const table = sortableTable([
      { label: 'verdict', value: r => r.verdict, render: r => verdictBadge(r.verdict) },
      ...(withReference ? [{ label: 'preventable', value: r => r.preventable || '', cls: 'preventable-cell' }] : []),
      { label: 'logical scenario', value: r => names.get(r.logical_uuid) || '' },
      { label: 'seed', value: r => r.seed, num: true },
      { label: 'values', value: r => r.values_text, cls: 'mono' },
      { label: 'sim time (s)', value: r => r.sim_time, num: true },
      { label: 'attempts', value: r => r.attempts, num: true },
      { label: 'reason', value: r => r.reason, cls: 'reason-cell' },
      { label: 'report', value: r => r.report || '', render: r => (r.report ? el('a', { href: r.report, text: 'open' }) : '–') },
    ], runs, { id: 'runs' });
    function filter() {
      const v = verdictSel.value, q = search.value.toLowerCase();
      table.show(runs.filter(r => (!v || r.verdict === v) && (!q || (r.values_text + ' ' + r.reason + ' ' + r.seed).toLowerCase().includes(q))));
    }
    verdictSel.addEventListener('change', filter);
    search.addEventListener('input', filter);
    c.append(el('div', { class: 'controls' }, verdictSel, search), el('div', { class: 'run-table' }, table));
    return c;
  }

  app.append(header(), ...(B.logical_scenarios || []).map(scenarioSection), runsTable(),
    el('footer', { text: `report.html written by orchestrator ${B.orchestrator_version} · Chart.js ${Chart.version}` }));
})();
