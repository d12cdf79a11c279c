// report.html of one run: header, map with trajectories, replay, time series, log.
'use strict';
(function () {
  const R = REPORT.result;
  const actors = REPORT.actors || [];
  const ego = actors.find(a => a.ego) || actors[0];
  const scenes = R.scenes || [];
  const events = R.events || [];
  // An OpenSCENARIO run: its storyboard's transitions instead of scenes (docs/openscenario.md "Report").
  const storyboard = events.some(e => e.kind === 'storyboard');
  const elementType = (e) => e.text.split(' ')[0];
  const app = document.getElementById('app');
  const step = R.step || 0.05;
  const tStart = actors.length ? Math.min(...actors.map(a => a.time.length ? a.time[0] : Infinity)) : 0;
  const tEnd = actors.length ? Math.max(...actors.map(a => a.time.length ? a.time[a.time.length - 1] : 0)) : 0;
  const SCENE_COLORS = ['#4e79a7', '#f28e2b', '#59a14f', '#e15759', '#76b7b2', '#edc948', '#b07aa1', '#ff9da7', '#9c755f', '#bab0ac'];
  const sceneColor = (id) => SCENE_COLORS[((id % SCENE_COLORS.length) + SCENE_COLORS.length) % SCENE_COLORS.length];
  // Scenario actors have numbers (the ego is 0), OpenSCENARIO entities their names.
  const actorName = (a) => (typeof a.actor_id === 'string' ? (a.ego ? 'ego ' : '') + a.actor_id : a.ego ? 'ego' : 'actor ' + a.actor_id) +
    (a.description ? ' — ' + a.description : '');

  // ------------------------------------------------------------------ state at a time
  // The trace's own row at time t (the last row not after t): no interpolation, so what the
  // replay shows is exactly what the trace recorded.
  function indexAt(times, t) {
    let lo = 0, hi = times.length - 1;
    if (hi < 0 || t < times[0] - 1e-9) return -1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (times[mid] <= t + 1e-9) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  function stateAt(a, t) {
    const i = indexAt(a.time, t);
    if (i < 0 || t > a.time[a.time.length - 1] + step * 1.5) return null;  // not (yet / any more) present
    return { i, time: a.time[i], x: a.x[i], y: a.y[i], heading: a.heading[i], speed: a.speed[i], accel: a.accel[i],
             lat: a.lat_offset[i], scene: a.scene_id[i] };
  }
  function sceneAt(t) {
    let current = scenes[0];
    for (const s of scenes) if (s.enter_time <= t + 1e-9) current = s;
    return current;
  }
  function boxCorners(x, y, heading, length, width) {
    const c = Math.cos(heading), s = Math.sin(heading), hl = length / 2, hw = width / 2;
    return [[hl, hw], [hl, -hw], [-hl, -hw], [-hl, hw]].map(([u, v]) => [x + u * c - v * s, y + u * s + v * c]);
  }
  const pointsText = (pts) => pts.map(p => p[0].toFixed(3) + ',' + p[1].toFixed(3)).join(' ');

  // ------------------------------------------------------------------ header
  function header() {
    const c = card(null);
    c.append(el('h1', { text: R.title || '(untitled scenario)' }));
    if (R.description) c.append(el('div', { class: 'muted', text: R.description }));
    c.append(el('div', { class: 'reason' }, verdictBadge(R.verdict), ' ', R.verdict === 'error' ? '' : (R.reason || '')));
    if (R.verdict === 'error') c.append(el('div', { class: 'error-box', id: 'run-error', text: R.reason || 'no reason given' }));
    const failing = (R.criteria || []).filter(k => !k.success);
    if (failing.length) {
      c.append(el('h3', { text: 'Failing criteria' }));
      c.append(criteriaTable(failing));
    }
    const ending = storyboard ? ['storyboard end', storyboardEnd()]
      : ['ending scene', R.ending_scene === null || R.ending_scene === undefined ? 'none' : 'scene ' + R.ending_scene];
    const meta = [['ego driven by', R.ego_model], ['seed', R.seed], ['backend', R.backend], ['map', R.map_id], ['simulated', fmtNum(R.sim_time, 2) + ' s'],
      ['steps', R.steps + ' × ' + step + ' s'], ending, ['traffic', trafficText()],
      ['wall time', fmtNum(R.wall_time_s, 2) + ' s'], ['SUMO', R.sumo_version], ['orchestrator', R.orchestrator_version]];
    c.append(el('div', { class: 'meta' }, meta.map(([k, v]) => el('div', {}, el('span', { text: k }), v === undefined ? '–' : String(v)))));
    if (ST) {
      c.append(el('h3', { text: 'Traffic actions (SUMO drives their vehicles)' }));
      c.append(trafficActionsTable());
    }
    const inputs = Object.entries(R.inputs || {}).filter(([, f]) => f && f.path);
    if (inputs.length) {
      c.append(el('h3', { text: 'Inputs' }));
      c.append(el('table', {}, el('tr', {}, el('th', { text: 'input' }), el('th', { text: 'path' }), el('th', { text: 'sha256' })),
        inputs.map(([k, f]) => el('tr', {}, el('td', { text: k }), el('td', { class: 'mono', text: f.path }),
          el('td', { class: 'mono', title: f.sha256 || '', text: (f.sha256 || '').slice(0, 16) + '…' })))));
    }
    for (const p of REPORT.problems || []) c.append(el('div', { class: 'problem', text: p }));
    for (const w of R.warnings || []) c.append(el('div', { class: 'problem', text: 'validation warning: ' + w }));
    return c;
  }

  // The run's traffic in a few words: the background (--traffic) and the storyboard's
  // TrafficActions with what they did, e.g. "swarm (300 spawned, 248 removed)".
  const ST = R.storyboard_traffic || null;
  function trafficText() {
    const parts = [];
    if (R.traffic && R.traffic !== 'none') parts.push('background ' + R.traffic);
    if (ST) {
      const kinds = [...new Set(ST.actions.map(a => a.kind))].join(' + ');
      const counts = [ST.spawned + ' spawned', ST.removed + ' removed'];
      if (ST.removed_background) counts.push(ST.removed_background + ' of them background');
      parts.push(kinds + ' (' + counts.join(', ') + ')');
    }
    return parts.length ? parts.join('; ') : 'none';
  }
  // One row per TrafficAction: what it is, when it ran, what became of its vehicles.
  function trafficActionsTable() {
    const head = ['traffic', 'kind', 'from (s)', 'to (s)', 'spawned', 'removed', 'left (route end)', 'not inserted', 'at end'];
    return el('table', { id: 'traffic-actions' }, el('tr', {}, head.map(h => el('th', { text: h }))),
      ST.actions.map(a => el('tr', { 'data-traffic': a.label }, el('td', { text: a.label }), el('td', { text: a.kind }),
        el('td', { class: 'num', text: fmtNum(a.started, 2) }), el('td', { class: 'num', text: a.stopped === null ? 'end' : fmtNum(a.stopped, 2) }),
        el('td', { class: 'num', text: a.kind === 'sink' ? '–' : String(a.spawned) }),
        el('td', { class: 'num', text: String(a.removed) + (a.kind === 'sink' && a.removed_background ? ` (${a.removed_background} background)` : '') }),
        el('td', { class: 'num', text: a.kind === 'sink' ? '–' : String(a.left) }),
        el('td', { class: 'num', text: a.kind === 'sink' ? '–' : String(a.not_inserted) }),
        el('td', { class: 'num', text: a.kind === 'sink' ? '–' : String(a.active_at_end) }))));
  }

  // How the storyboard ended: its StopTrigger (or not), and the last element that ran.
  function storyboardEnd() {
    const stop = events.find(e => e.kind === 'storyboard' && elementType(e) === 'storyboard');
    const elements = events.filter(e => e.kind === 'storyboard' && elementType(e) !== 'storyboard');
    const last = elements.length ? elements[elements.length - 1] : null;
    return (stop ? 'StopTrigger at ' + fmtNum(stop.time, 2) + ' s' : 'no StopTrigger') +
      (last ? '; last: ' + last.text + ' at ' + fmtNum(last.time, 2) + ' s' : '');
  }

  function criteriaTable(list) {
    return el('table', { class: 'criteria' }, el('tr', {}, ['criterion', 'actor', 'metric', 'expected', 'actual', 'at', 'result'].map(h => el('th', { text: h }))),
      list.map(k => el('tr', {}, el('td', { text: k.name }), el('td', { text: k.actor }), el('td', { text: k.metric }),
        el('td', { text: typeof k.expected === 'object' ? JSON.stringify(k.expected) : k.expected }),
        el('td', { class: 'num', text: fmtCell(k.actual) }), el('td', { class: 'num', text: k.at_time === null || k.at_time === undefined ? '–' : fmtNum(k.at_time, 2) + ' s' }),
        el('td', {}, verdictBadge(k.success ? 'success' : 'failure')))));
  }

  // ------------------------------------------------------------------ map views
  // One SVG drawing of lanes, trajectories, markers and boxes in map coordinates (y up), with
  // its own pan and zoom; `follow` keeps the ego in the middle at a fixed scale (the replay).
  function mapView(id, follow) {
    const svg = svgEl('svg', { class: 'map', id });
    const view = svgEl('g', { class: 'view' });
    svg.append(view);
    const lanes = svgEl('g', { class: 'lanes' });
    for (const l of REPORT.lanes || []) {
      lanes.append(svgEl('polyline', { class: 'lane' + (l.internal ? ' internal' : ''), 'data-lane': l.id,
        points: l.xy.reduce((s, v, i) => s + (i % 2 ? ',' : (i ? ' ' : '')) + v, ''), 'stroke-width': Math.max(0.5, l.width - 0.25) }));  // the gap marks the lane's border
    }
    view.append(lanes);
    const trajectories = svgEl('g', { class: 'trajectories' });
    for (const a of actors) {
      const pts = [];
      for (let i = 0; i < a.x.length; i++) if (a.x[i] !== null) pts.push(a.x[i] + ',' + a.y[i]);
      const line = svgEl('polyline', { class: 'trajectory', 'data-actor': a.actor_id, stroke: a.color, points: pts.join(' '),
        'vector-effect': 'non-scaling-stroke' });
      line.append(svgEl('title', {}));
      line.lastChild.textContent = actorName(a);
      trajectories.append(line);
    }
    view.append(trajectories);
    const markers = svgEl('g', { class: 'markers' });
    const addMarker = (cls, x, y, color, text) => {
      const m = svgEl('circle', { class: cls, cx: x, cy: y, r: 1, stroke: color, 'vector-effect': 'non-scaling-stroke' });
      const title = svgEl('title', {});
      title.textContent = text;
      m.append(title);
      markers.append(m);
    };
    for (const s of scenes.slice(1)) for (const a of actors) {
      const st = stateAt(a, s.enter_time);
      if (st) addMarker('marker-scene', st.x, st.y, a.color, `t=${fmtNum(s.enter_time, 2)} s: scene ${s.scene_id} "${s.description}" (${actorName(a)})`);
    }
    for (const c of R.collisions || []) for (const p of c.positions || [])
      addMarker('marker-collision', p[0], p[1], '#fff', `t=${fmtNum(c.time, 2)} s: collision ${c.between.join(' – ')} (${c.source}${c.counted ? '' : ', not counted'})`);
    for (const c of R.lane_change_conflicts || [])
      addMarker('marker-conflict', c.positions[1][0], c.positions[1][1], '#fff', `t=${fmtNum(c.time, 2)} s: ${c.vehicle} ${c.vehicle_is} actor ${c.actor} in its lane change (gap ${fmtNum(c.gap, 1)} m)`);
    view.append(markers);
    const bgBoxes = svgEl('g', { class: 'background' });
    view.append(bgBoxes);
    const trafficBoxes = svgEl('g', { class: 'traffic-actions' });
    view.append(trafficBoxes);
    const boxes = svgEl('g', { class: 'boxes' });
    const boxOf = new Map();
    for (const a of actors.slice().reverse()) {
      const b = svgEl('polygon', { class: 'actor-box', 'data-actor': a.actor_id, fill: a.color, 'vector-effect': 'non-scaling-stroke' });
      boxes.append(b);
      boxOf.set(a.actor_id, b);
    }
    view.append(boxes);

    // Bounds of what there is to see: the trajectories (the lanes around them are context).
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
    for (const a of actors) for (let i = 0; i < a.x.length; i++) {
      if (a.x[i] === null) continue;
      minX = Math.min(minX, a.x[i]); maxX = Math.max(maxX, a.x[i]); minY = Math.min(minY, a.y[i]); maxY = Math.max(maxY, a.y[i]);
    }
    const state = { scale: 1, cx: (minX + maxX) / 2, cy: (minY + maxY) / 2, follow };
    function fit() {
      const w = svg.clientWidth || 600, h = svg.clientHeight || 460;
      state.scale = Math.min(w / Math.max(maxX - minX + 40, 40), h / Math.max(maxY - minY + 40, 40));
      state.cx = (minX + maxX) / 2; state.cy = (minY + maxY) / 2;
    }
    function apply() {
      const w = svg.clientWidth || 600, h = svg.clientHeight || 460, s = state.scale;
      view.setAttribute('transform', `matrix(${s},0,0,${-s},${w / 2 - s * state.cx},${h / 2 + s * state.cy})`);
      const r = (follow ? 4 : 5) / s;
      for (const m of markers.children) m.setAttribute('r', r);
    }
    if (follow) state.scale = 4; else fit();
    // Pan by dragging, zoom by the wheel around the pointer.
    let drag = null;
    svg.addEventListener('mousedown', (e) => { drag = { x: e.clientX, y: e.clientY, cx: state.cx, cy: state.cy }; state.follow = false; });
    window.addEventListener('mouseup', () => { drag = null; });
    window.addEventListener('mousemove', (e) => {
      if (!drag) return;
      state.cx = drag.cx - (e.clientX - drag.x) / state.scale;
      state.cy = drag.cy + (e.clientY - drag.y) / state.scale;
      apply();
    });
    svg.addEventListener('wheel', (e) => {
      e.preventDefault();
      const f = Math.exp(-e.deltaY * 0.0015);
      const rect = svg.getBoundingClientRect();
      const px = e.clientX - rect.left - rect.width / 2, py = e.clientY - rect.top - rect.height / 2;
      state.cx += px / state.scale - px / (state.scale * f);
      state.cy -= py / state.scale - py / (state.scale * f);
      state.scale *= f;
      apply();
    }, { passive: false });
    svg.addEventListener('dblclick', () => { if (follow) state.follow = true; else fit(); apply(); });

    function update(t) {
      for (const a of actors) {
        const st = stateAt(a, t), b = boxOf.get(a.actor_id);
        if (!st || st.x === null) { b.setAttribute('visibility', 'hidden'); continue; }
        b.setAttribute('visibility', 'visible');
        // On the overview the boxes are too small to see: drawn at least 3 px long there.
        const grow = follow ? 1 : Math.max(1, 3 / (a.length * state.scale));
        b.setAttribute('points', pointsText(boxCorners(st.x, st.y, st.heading, a.length * grow, a.width * grow)));
        b.setAttribute('data-time', st.time);
        if (a === ego && state.follow) { state.cx = st.x; state.cy = st.y; }
      }
      // On the overview drawn at least 3 px long, as the actors.
      const grow = (length) => follow ? 1 : Math.max(1, 3 / (length * state.scale));
      drawVehicles(bgSet, bgBoxes, 'bg-box', t, grow);
      drawVehicles(trafficSet, trafficBoxes, 'traffic-box', t, grow);
      apply();
    }
    return { svg, update, fit: () => { if (!follow) fit(); apply(); } };
  }

  // Vehicles that are no scenario actors at time t: the rows of the last traced step not after
  // t. The background (background.csv, --trace-background) and the storyboard's TrafficAction
  // vehicles (traffic_actions.csv) are drawn the same way, each in its own colour.
  function vehicleSet(rows) {
    if (!rows) return null;
    const steps = [];
    for (let i = 0; i < rows.time.length; i++) if (!steps.length || rows.time[steps[steps.length - 1]] !== rows.time[i]) steps.push(i);
    return { rows, steps, times: steps.map(i => rows.time[i]) };
  }
  const bgSet = vehicleSet(REPORT.background), trafficSet = vehicleSet(REPORT.traffic_actions);
  const trafficLabel = (k) => ST && ST.actions[k - 1] ? ST.actions[k - 1].label : '';
  function drawVehicles(set, group, cls, t, grow) {
    if (!set) return;
    const v = set.rows, k = indexAt(set.times, t);
    // A step without rows (none in SUMO then, or the file ended before the trace): none drawn.
    const gone = k >= 0 && t > set.times[k] + step * ((v.stride_steps || 1) + 0.5);
    const from = k < 0 || gone ? 0 : set.steps[k], to = k < 0 || gone ? 0 : (k + 1 < set.steps.length ? set.steps[k + 1] : v.time.length);
    while (group.children.length < to - from) group.append(svgEl('polygon', { class: cls, 'vector-effect': 'non-scaling-stroke' }));
    for (let j = 0; j < group.children.length; j++) {
      const p = group.children[j], i = from + j;
      if (i >= to) { p.setAttribute('visibility', 'hidden'); continue; }
      p.setAttribute('visibility', 'visible');
      const g = grow(v.length[i]);
      p.setAttribute('points', pointsText(boxCorners(v.x[i], v.y[i], v.heading[i], v.length[i] * g, v.width[i] * g)));
      p.setAttribute('data-vehicle', v.vehicle_id[i]);
      if (v.traffic) p.setAttribute('data-traffic', trafficLabel(v.traffic[i]));
    }
  }

  // ------------------------------------------------------------------ time series
  const charts = [];
  let now = tStart;
  // Scene bands behind the lines, and the replay's time as a vertical line.
  const sceneBands = {
    id: 'sceneBands',
    beforeDatasetsDraw(chart) {
      const { ctx, chartArea: a, scales: { x } } = chart;
      ctx.save();
      scenes.forEach((s, i) => {
        const from = Math.max(x.getPixelForValue(s.enter_time), a.left);
        const to = Math.min(x.getPixelForValue(i + 1 < scenes.length ? scenes[i + 1].enter_time : tEnd), a.right);
        if (to <= from) return;
        ctx.fillStyle = sceneColor(s.scene_id) + '22';
        ctx.fillRect(from, a.top, to - from, a.bottom - a.top);
        ctx.fillStyle = sceneColor(s.scene_id);
        ctx.font = '10px sans-serif';
        if (to - from > 14) ctx.fillText(String(s.scene_id), from + 3, a.top + 10);
      });
      ctx.restore();
    },
    afterDatasetsDraw(chart) {
      const { ctx, chartArea: a, scales: { x } } = chart;
      const px = x.getPixelForValue(now);
      if (px < a.left || px > a.right) return;
      ctx.save();
      ctx.strokeStyle = '#111';
      ctx.setLineDash([4, 3]);
      ctx.beginPath(); ctx.moveTo(px, a.top); ctx.lineTo(px, a.bottom); ctx.stroke();
      ctx.restore();
    },
  };
  function lineChart(id, title, datasets, yTitle, extra) {
    const canvas = el('canvas', { id });
    const box = el('div', {}, el('h3', { text: title }), el('div', { class: 'chart-box' }, canvas));
    const chart = new Chart(canvas, {
      type: 'line',
      data: { datasets },
      options: Object.assign({
        parsing: false, normalized: true, spanGaps: false,
        elements: { point: { radius: 0 }, line: { borderWidth: 1.6 } },
        interaction: { mode: 'nearest', axis: 'x', intersect: false },
        scales: { x: { type: 'linear', min: Math.floor(tStart), max: tEnd, title: { display: true, text: 's' } },
                  y: { title: { display: true, text: yTitle } } },
        plugins: { tooltip: { callbacks: { title: (items) => 't = ' + fmtNum(items[0].parsed.x, 2) + ' s' } } },
        onClick: (e, items, chart) => setTime(chart.scales.x.getValueForPixel(e.x)),
      }, extra || {}),
      plugins: [sceneBands],
    });
    charts.push(chart);
    return box;
  }
  const series = (a, column, scale) => a.time.map((t, i) => ({ x: t, y: a[column][i] === null ? null : a[column][i] * (scale || 1) }));
  function timeSeries() {
    const c = card('Time series');
    if (!actors.length) { c.append(el('div', { class: 'muted', text: 'No trace: nothing was simulated.' })); return c; }
    const grid = el('div', { class: 'charts' });
    const perActor = (column, scale) => actors.map(a => ({ label: actorName(a), borderColor: a.color, backgroundColor: a.color, data: series(a, column, scale) }));
    grid.append(lineChart('chart-speed', 'Speed', perActor('speed', 3.6), 'km/h'));
    grid.append(lineChart('chart-accel', 'Acceleration', perActor('accel'), 'm/s²'));
    grid.append(lineChart('chart-lat', 'Lateral offset from the lane centre (+ left)', perActor('lat_offset'), 'm'));
    const m = REPORT.metrics && ego ? REPORT.metrics[String(ego.actor_id)] : null;
    if (m) {
      const ms = (col) => m.time.map((t, i) => ({ x: t, y: m[col] ? m[col][i] : null }));
      grid.append(lineChart('chart-gap', 'Ego: gap to the leader', [{ label: 'gap', borderColor: '#1f6fd1', data: ms('gap') }], 'm'));
      grid.append(lineChart('chart-ttc', 'Ego: time to collision and time headway', [
        { label: 'TTC', borderColor: '#d62f2f', data: ms('ttc') }, { label: 'THW', borderColor: '#2e9d46', data: ms('thw') }], 's',
        { scales: { x: { type: 'linear', min: Math.floor(tStart), max: tEnd, title: { display: true, text: 's' } }, y: { min: 0, suggestedMax: 6, max: 15, title: { display: true, text: 's' } } } }));
    }
    c.append(grid);
    c.append(timeline());
    return c;
  }
  // Scene transitions, actions and warnings over time; hovering shows the run-log line.
  function timeline() {
    const logLines = (REPORT.log || '').split('\n');
    const lineFor = (e) => logLines.find(l => l.includes(e.text) && l.includes(fmtNum(e.time, 3))) || ('t=' + fmtNum(e.time, 3) + '  ' + e.text);
    // A storyboard's transitions in two rows: Storyboard / Story / Act, and ManeuverGroup / Maneuver / Event.
    const rows = storyboard ? { act: 4, event: 3, action: 2, warning: 1, info: 0 } : { scene: 3, action: 2, warning: 1, info: 0 };
    const colors = { scene: '#1f6fd1', act: '#1f6fd1', event: '#9467bd', action: '#2e9d46', warning: '#e0a800', info: '#98a1ab' };
    const rowOf = (e) => e.kind !== 'storyboard' ? e.kind : (['storyboard', 'story', 'act'].includes(elementType(e)) ? 'act' : 'event');
    const datasets = Object.keys(rows).map(k => ({ label: k, backgroundColor: colors[k], borderColor: colors[k], pointRadius: 5, pointHoverRadius: 7,
      pointStyle: k === 'scene' || k === 'act' ? 'rectRot' : k === 'event' ? 'triangle' : 'circle',
      data: events.filter(e => rowOf(e) === k).map(e => ({ x: e.time, y: rows[k], text: lineFor(e) })) }));
    const canvas = el('canvas', { id: 'chart-timeline' });
    charts.push(new Chart(canvas, {
      type: 'scatter', data: { datasets },
      options: {
        scales: { x: { type: 'linear', min: Math.floor(tStart), max: tEnd }, y: { min: -0.5, max: Object.keys(rows).length - 0.5, afterBuildTicks: (axis) => { axis.ticks = Object.values(rows).map(v => ({ value: v })); },
              ticks: { callback: (v) => Object.keys(rows).find(k => rows[k] === v) || '' } } },
        plugins: { legend: { display: false }, tooltip: { callbacks: { label: (item) => item.raw.text } } },
        onClick: (e, items, chart) => setTime(chart.scales.x.getValueForPixel(e.x)) },
      plugins: [sceneBands] }));
    const title = storyboard ? 'Storyboard timeline: Acts, Events, actions starting and ending (hover for the run-log line)'
      : 'Scene timeline: transitions, actions, warnings (hover for the run-log line)';
    return el('div', {}, el('h3', { text: title }), el('div', { class: 'chart-box small' }, canvas));
  }

  // ------------------------------------------------------------------ replay
  let views = [];
  const slider = el('input', { type: 'range', id: 'time-slider', min: tStart, max: tEnd, step: step, value: tStart });
  const timeLabel = el('span', { id: 'time-label' });
  const sceneNow = el('div', { id: 'scene-now' });
  const readout = el('tbody', { id: 'replay-readout' });
  function setTime(t) {
    now = Math.min(Math.max(t, tStart), tEnd);
    slider.value = now;
    timeLabel.textContent = 't = ' + fmtNum(now, 2) + ' s';
    const s = sceneAt(now);
    sceneNow.textContent = s ? `scene ${s.scene_id}: ${s.description || '(no description)'}` : '';
    for (const v of views) v.update(now);
    readout.replaceChildren(...actors.map(a => {
      const st = stateAt(a, now);
      return el('tr', { 'data-actor': a.actor_id }, el('td', {}, el('i', { style: 'display:inline-block;width:10px;height:10px;background:' + a.color }), ' ', actorName(a)),
        el('td', { class: 'num x', text: st ? fmtNum(st.x, 3) : '–' }), el('td', { class: 'num y', text: st ? fmtNum(st.y, 3) : '–' }),
        el('td', { class: 'num', text: st ? fmtNum(st.heading * 180 / Math.PI, 1) : '–' }),
        el('td', { class: 'num', text: st ? fmtNum(st.speed * 3.6, 1) : '–' }), el('td', { class: 'num', text: st ? fmtNum(st.accel, 2) : '–' }),
        el('td', { class: 'num', text: st ? fmtNum(st.lat, 2) : '–' }));
    }));
    for (const ch of charts) ch.draw();
  }
  function mapAndReplay() {
    const c = card('Map and replay');
    if (!actors.length) {
      c.append(el('div', { class: 'muted', text: 'No trace: the run ended before its first step, so there is nothing to draw.' }));
      return c;
    }
    const overview = mapView('map-overview', false), replay = mapView('map-replay', true);
    views = [overview, replay];
    c.append(el('div', { class: 'legend' }, actors.map(a => el('span', {}, el('i', { style: 'background:' + a.color }), actorName(a) +
      (a.size_known ? ` (${fmtNum(a.length, 1)} × ${fmtNum(a.width, 1)} m)` : ''))),
      bgSet ? el('span', {}, el('i', { class: 'legend-bg' }), 'background vehicles (near the actors)') : null,
      trafficSet ? el('span', {}, el('i', { class: 'legend-traffic' }), 'TrafficAction vehicles (' + ST.actions.filter(a => a.kind !== 'sink').map(a => a.label).join(', ') + ')') : null,
      el('span', { class: 'muted', text: '○ scene change  ● collision  ● lane-change conflict (orange) · drag to pan, wheel to zoom, double-click to reset' })));
    c.append(el('div', { class: 'row' }, el('div', {}, el('h3', { text: 'Trajectories' }), overview.svg),
      el('div', {}, el('h3', { text: 'Replay (follows the ego)' }), replay.svg)));
    let playing = false, last = 0;
    const speedSel = el('select', { id: 'play-speed' }, ['0.5', '1', '2', '5', '10'].map(s => el('option', { value: s, text: s + '×', selected: s === '2' ? '' : null })));
    const play = el('button', { id: 'play', text: '▶ play', onclick: () => {
      playing = !playing;
      play.textContent = playing ? '❚❚ pause' : '▶ play';
      if (playing && now >= tEnd) setTime(tStart);
      last = performance.now();
      if (playing) requestAnimationFrame(tick);
    } });
    function tick(ts) {
      if (!playing) return;
      setTime(now + (ts - last) / 1000 * Number(speedSel.value));
      last = ts;
      if (now >= tEnd) { playing = false; play.textContent = '▶ play'; return; }
      requestAnimationFrame(tick);
    }
    slider.addEventListener('input', () => setTime(Number(slider.value)));
    c.append(el('div', { class: 'controls' }, play, speedSel, slider, timeLabel), sceneNow);
    c.append(el('table', {}, el('thead', {}, el('tr', {}, ['actor', 'x (m)', 'y (m)', 'heading (°)', 'speed (km/h)', 'accel (m/s²)', 'lat. offset (m)'].map(h => el('th', { text: h })))), readout));
    return c;
  }

  // ------------------------------------------------------------------ log and events
  function logSection() {
    const c = card('Run log and events');
    const search = el('input', { type: 'search', id: 'log-search', placeholder: 'search the log and the events…' });
    const log = el('div', { class: 'log', id: 'run-log' });
    const lines = (REPORT.log || '').split('\n').filter(l => l.length);
    const eventRows = events.map(e => ({ time: e.time, kind: e.kind, text: e.text }));
    const table = sortableTable([{ label: 'time (s)', value: r => r.time, num: true }, { label: 'kind', value: r => r.kind },
      { label: 'text', value: r => r.text }], eventRows, { id: 'events' });
    function filter() {
      const q = search.value.toLowerCase();
      log.replaceChildren(...lines.filter(l => !q || l.toLowerCase().includes(q)).map(l => el('div', { class: q ? 'hit' : null, text: l })));
      table.show(eventRows.filter(r => !q || r.text.toLowerCase().includes(q) || r.kind.includes(q)));
    }
    search.addEventListener('input', filter);
    filter();
    c.append(el('div', { class: 'controls' }, search, el('span', { class: 'muted', text: lines.length + ' log lines, ' + events.length + ' events' })));
    c.append(el('h3', { text: 'run.log' }), log, el('h3', { text: 'Events (result.json)' }), el('div', { class: 'run-table' }, table));
    if ((R.criteria || []).length) c.append(el('h3', { text: 'All criteria' }), criteriaTable(R.criteria));
    return c;
  }

  app.append(header(), mapAndReplay(), timeSeries(), logSection(),
    el('footer', { text: `report.html written by orchestrator ${REPORT.orchestrator_version} · Chart.js ${Chart.version}` }));
  for (const v of views) v.fit();
  setTime(tStart);
  // For scripts and tests: move the replay and read what it shows.
  window.orchReport = { setTime, stateAt: (id, t) => stateAt(actors.find(a => a.actor_id === id), t), tStart, tEnd };
})();
