// The snooker shot planner's page: draws the table from GetModel, lets the balls be
// placed, plans through PlanStream and replays a shot through Simulate. It talks
// only to the server that serves it (the Connect protocol, JSON), nothing else.
// Frame and units as in proto/snooker/v1: metres in the table frame (x across from
// the left cushion nose, y along from the baulk cushion nose), degrees counter-
// clockwise from +x. The SVG draws the table with the baulk end on the left.
'use strict';

const SERVICE = '/snooker.v1.ShotPlanner/';
const SVG_NS = 'http://www.w3.org/2000/svg';
const KINDS = ['CUE', 'RED', 'YELLOW', 'GREEN', 'BROWN', 'BLUE', 'PINK', 'BLACK'];
const COLOUR_IDS = { YELLOW: 'yellow', GREEN: 'green', BROWN: 'brown', BLUE: 'blue', PINK: 'pink', BLACK: 'black' };
const PLACED_CUE_ID = 'cue';  // the planner's name for the cue ball placed from hand

// Noise presets: NoiseModel (plan.proto), one standard deviation of each error.
//  * robot: the server's defaults (planner/pot_estimate.h, argued in
//    docs/planning-notes.md section 3.3): a calibrated arm with a rigid cue.
//  * professional: the computer pool championships' noise (docs/planning-notes.md
//    section 3.1): 0.125 deg of aim, 0.5 mm on each tip offset, 0.1 deg of elevation
//    and 0.075 m/s of speed (3 % of a 2.5 m/s shot), about a top player's cueing.
//  * club player: the championships' "high noise" class, five times those.
// Vision (0.2 mm, calibrated overhead cameras) and the model's own uncertainty in
// squirt and throw belong to the table, not the player: the same in every preset.
const NOISE_PRESETS = {
  robot: {
    aimSigmaDeg: 0.02, cueSpeedSigmaFraction: 0.01, tipOffsetSigmaMm: 0.1, elevationSigmaDeg: 0.1,
    positionSigmaMm: 0.2, squirtSigmaFraction: 0.15, throwSigmaFraction: 0.1,
  },
  professional: {
    aimSigmaDeg: 0.125, cueSpeedSigmaFraction: 0.03, tipOffsetSigmaMm: 0.5, elevationSigmaDeg: 0.1,
    positionSigmaMm: 0.2, squirtSigmaFraction: 0.15, throwSigmaFraction: 0.1,
  },
  club: {
    aimSigmaDeg: 0.625, cueSpeedSigmaFraction: 0.15, tipOffsetSigmaMm: 2.5, elevationSigmaDeg: 0.5,
    positionSigmaMm: 0.2, squirtSigmaFraction: 0.15, throwSigmaFraction: 0.1,
  },
};

// ---------------------------------------------------------------------------
// The Connect protocol (unary and server streaming, JSON).

// `requestId`: the X-Request-Id the server named the call by (its log line has it).
class ConnectError extends Error {
  constructor(code, message, requestId = '') {
    super(message);
    this.name = 'ConnectError';
    this.code = code;
    this.requestId = requestId || '';
  }
}

function errorOf(response, text) {
  const id = response.headers.get('X-Request-Id');
  let body = null;
  try { body = JSON.parse(text); } catch (_) { /* not JSON: said below */ }
  if (body && typeof body.message === 'string' && body.message) {
    return new ConnectError(body.code || 'unknown', body.message, id);
  }
  if (body && typeof body.code === 'string') return new ConnectError(body.code, body.code.replace(/_/g, ' '), id);
  const tail = text ? ': ' + text.slice(0, 300) : '';
  return new ConnectError('unknown', `the server answered HTTP ${response.status} ${response.statusText}${tail}`, id);
}

async function callUnary(method, request, signal) {
  const response = await fetch(SERVICE + method, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', 'Connect-Protocol-Version': '1' },
    body: JSON.stringify(request),
    signal,
  });
  const text = await response.text();
  if (!response.ok) throw errorOf(response, text);
  try {
    return JSON.parse(text);
  } catch (_) {
    throw new ConnectError('internal', `${method}'s answer is not JSON: ${text.slice(0, 200)}`,
      response.headers.get('X-Request-Id'));
  }
}

// Calls a server-streaming method; onMessage gets each message in order. Resolves
// at the end of the stream, rejects with a ConnectError (or the AbortError of
// `signal`).
async function callStream(method, request, signal, onMessage) {
  const json = new TextEncoder().encode(JSON.stringify(request));
  const body = new Uint8Array(5 + json.length);
  new DataView(body.buffer).setUint32(1, json.length);
  body.set(json, 5);
  const response = await fetch(SERVICE + method, {
    method: 'POST',
    headers: { 'Content-Type': 'application/connect+json', 'Connect-Protocol-Version': '1' },
    body,
    signal,
  });
  if (!response.ok) throw errorOf(response, await response.text());
  const id = response.headers.get('X-Request-Id');
  const reader = response.body.getReader();
  const decoder = new TextDecoder();
  let buffer = new Uint8Array(0);
  for (;;) {
    const { done, value } = await reader.read();
    if (value && value.length) {
      const joined = new Uint8Array(buffer.length + value.length);
      joined.set(buffer);
      joined.set(value, buffer.length);
      buffer = joined;
    }
    while (buffer.length >= 5) {
      const flags = buffer[0];
      const length = new DataView(buffer.buffer, buffer.byteOffset, 5).getUint32(1);
      if (buffer.length < 5 + length) break;
      const text = decoder.decode(buffer.subarray(5, 5 + length));
      buffer = buffer.slice(5 + length);
      if (flags & 1) throw new ConnectError('internal', 'the server sent a compressed message', id);
      let message;
      try {
        message = JSON.parse(text);
      } catch (_) {
        throw new ConnectError('internal', `${method} sent a message that is not JSON: ${text.slice(0, 200)}`, id);
      }
      if (flags & 2) {  // end of stream
        reader.cancel().catch(() => {});
        if (message && message.error) {
          const e = message.error;
          throw new ConnectError(e.code || 'unknown', e.message || (e.code || 'unknown error').replace(/_/g, ' '), id);
        }
        return;
      }
      onMessage(message);
    }
    if (done) break;
  }
  throw new ConnectError('unavailable', `${method}'s stream ended without its end message`, id);
}

// ---------------------------------------------------------------------------
// State.

const state = {
  model: null,            // GetModelResponse
  builtinTables: {},      // name -> the balls of GetModel's built-in table
  radius: 0.02625,        // m, the model's ball radius
  balls: [],              // [{id, kind, x, y}]
  selectedId: null,
  planController: null,
  planSeq: 0,
  planned: null,          // {request, balls, response} of the last finished plan
  selectedShot: -1,
  replayController: null,
  replay: null,           // {shotIndex, paths, kinds, duration, finalBalls, events, t, playing}
  replayActive: false,
  drag: null,
  firstPlanDone: false,
};

// What the browser test reads: timings (performance.now() ms, from navigation start)
// and the last plan's request and answer.
const debugInfo = {
  planSeq: 0,
  firstPlanMs: null,
  lastPlan: null,         // {seq, trigger, startMs, endMs, ms, serverMs, final}
  lastPlanRequest: null,
  lastPlanResponse: null,
  replaySeq: 0,
  progressShown: 0,       // progress messages drawn (the best shot so far)
  builtinTables: null,    // as GetModel gave them, by name
};
window.snookerPage = debugInfo;

const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------------------
// Small helpers.

function svg(tag, attrs, parent) {
  const e = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, String(v));
  if (parent) parent.appendChild(e);
  return e;
}

function html(tag, props, children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(props || {})) {
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else if (k.startsWith('data-')) e.setAttribute(k, v);
    else e[k] = v;
  }
  for (const c of children || []) e.append(c);
  return e;
}

const num = (v) => (typeof v === 'number' && Number.isFinite(v) ? v : Number(v) || 0);
const vec = (v) => ({ x: num(v && v.x), y: num(v && v.y) });
const kindClass = (kind) => 'k-' + (KINDS.includes(kind) ? kind : 'other');
const pct = (p) => (100 * num(p)).toFixed(1) + ' %';
const fixed = (v, digits) => num(v).toFixed(digits);
const words = (s) => String(s || '').toLowerCase().replace(/_/g, '-');

function kindOfId(id, balls) {
  const b = (balls || state.balls).find((x) => x.id === id);
  if (b) return b.kind;
  return id === PLACED_CUE_ID ? 'CUE' : null;
}

// A ball's id with a dot of its colour: the name it has on the table.
function ballLabel(id, balls) {
  if (!id) return document.createTextNode('—');
  const span = html('span', { class: 'ball-name' });
  span.append(html('span', { class: 'dot ' + kindClass(kindOfId(id, balls)) }), id);
  return span;
}

function pointAt(path, t) {
  const ts = path.t || [];
  const ps = path.points || [];
  if (!ps.length) return null;
  if (t <= num(ts[0])) return vec(ps[0]);
  const last = ps.length - 1;
  if (t >= num(ts[last])) return vec(ps[last]);
  let lo = 0, hi = last;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (num(ts[mid]) <= t) lo = mid; else hi = mid;
  }
  const t0 = num(ts[lo]), t1 = num(ts[hi]);
  const a = vec(ps[lo]), b = vec(ps[hi]);
  const f = t1 > t0 ? (t - t0) / (t1 - t0) : 0;
  return { x: a.x + f * (b.x - a.x), y: a.y + f * (b.y - a.y) };
}

// ---------------------------------------------------------------------------
// Messages.

function setStatus(text) { $('status').textContent = text; }

function showError(text) {
  const box = $('error');
  box.textContent = text;
  box.hidden = false;
}

function clearError() {
  $('error').hidden = true;
  $('error').textContent = '';
}

function errorText(e) {
  if (e instanceof ConnectError) {
    return `${e.code.replace(/_/g, ' ')}: ${e.message}` + (e.requestId ? ` (request id ${e.requestId})` : '');
  }
  if (e instanceof TypeError) return `cannot reach the server: ${e.message}`;
  return String(e && e.message ? e.message : e);
}

function showWarnings(warnings) {
  const box = $('warnings');
  const list = (warnings || []).map((w) => w.message).filter(Boolean);
  box.textContent = list.length ? 'Vision repair: ' + list.join('; ') : '';
  box.hidden = list.length === 0;
}

// ---------------------------------------------------------------------------
// The table.

function drawTable() {
  const t = state.model.table;
  const w = num(t.widthM), l = num(t.lengthM);
  const m = 0.12;  // wood and cushions around the bed, m
  $('table').setAttribute('viewBox', `${-m} ${-m} ${l + 2 * m} ${w + 2 * m}`);
  const g = $('layer-table');
  g.replaceChildren();
  svg('rect', { class: 'wood', x: -m, y: -m, width: w + 2 * m, height: l + 2 * m, rx: 0.04 }, g);
  svg('rect', { class: 'rail', x: -0.05, y: -0.05, width: w + 0.1, height: l + 0.1 }, g);
  svg('rect', { class: 'bed', x: 0, y: 0, width: w, height: l }, g);
  const segments = t.segments || [];
  for (const p of t.pockets || []) {
    // The pocket's channel between its jaw walls, then the hole.
    const walls = segments.filter((s) => s.kind === 'jaw wall' && s.pocket === p.name);
    const points = walls.flatMap((s) => [vec(s.p0), vec(s.p1)]);
    if (points.length >= 3) {
      const c = points.reduce((a, q) => ({ x: a.x + q.x / points.length, y: a.y + q.y / points.length }), { x: 0, y: 0 });
      points.sort((a, b) => Math.atan2(a.y - c.y, a.x - c.x) - Math.atan2(b.y - c.y, b.x - c.x));
      svg('polygon', { class: 'pocket', points: points.map((q) => `${q.x},${q.y}`).join(' ') }, g);
    }
    const cc = vec(p.captureCentre);
    svg('title', {}, svg('circle', { class: 'pocket', cx: cc.x, cy: cc.y, r: num(p.captureRadiusM) }, g)).textContent = p.name;
  }
  for (const s of segments) {
    const a = vec(s.p0), b = vec(s.p1);
    svg('line', { class: s.kind === 'jaw wall' ? 'jaw' : 'nose', x1: a.x, y1: a.y, x2: b.x, y2: b.y }, g);
  }
  for (const k of t.knuckles || []) {
    const c = vec(k.centre);
    svg('circle', { class: 'knuckle', cx: c.x, cy: c.y, r: num(k.radiusM) }, g);
  }
  const baulk = num(t.baulkLineM), d = num(t.dRadiusM), cx = w / 2;
  svg('line', { class: 'marking', x1: 0, y1: baulk, x2: w, y2: baulk }, g);
  // The D: the half circle on the baulk side of the line (y below it).
  svg('path', { class: 'marking', d: `M ${cx - d} ${baulk} A ${d} ${d} 0 0 0 ${cx + d} ${baulk}` }, g);
  for (const s of t.spots || []) {
    const p = vec(s.position);
    svg('circle', { class: 'spot', cx: p.x, cy: p.y, r: 0.006 }, g);
  }
}

function toTable(event) {
  const m = $('frame').getScreenCTM();
  if (!m) return null;
  const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(m.inverse());
  return { x: p.x, y: p.y };
}

function clampToBed(p) {
  const t = state.model ? state.model.table : { widthM: 1.778, lengthM: 3.569 };
  const c = num(t.cushionContactDistanceM) || state.radius;
  return {
    x: Math.min(Math.max(p.x, c), num(t.widthM) - c),
    y: Math.min(Math.max(p.y, c), num(t.lengthM) - c),
  };
}

function cueInHand() { return $('cue-in-hand').checked; }

function drawBalls() {
  const g = $('layer-balls');
  g.replaceChildren();
  for (const b of state.balls) {
    const classes = ['ball', kindClass(b.kind)];
    if (b.id === state.selectedId) classes.push('selected');
    if (b.kind === 'CUE' && cueInHand()) classes.push('in-hand');
    const c = svg('circle', { class: classes.join(' '), cx: b.x, cy: b.y, r: state.radius, 'data-id': b.id }, g);
    svg('title', {}, c).textContent = `${b.id} (${words(b.kind)}) at (${b.x.toFixed(3)}, ${b.y.toFixed(3)}) m`;
  }
  $('remove-ball').disabled = !state.balls.some((b) => b.id === state.selectedId);
}

function onBallPointerDown(event) {
  const target = event.target.closest('circle.ball');
  if (!target || event.button > 0) return;
  const ball = state.balls.find((b) => b.id === target.dataset.id);
  if (!ball) return;
  event.preventDefault();
  endReplayView();
  const p = toTable(event);
  if (!p) return;
  target.setPointerCapture(event.pointerId);
  target.classList.add('dragging');
  state.drag = { ball, element: target, pointerId: event.pointerId, dx: ball.x - p.x, dy: ball.y - p.y, moved: false, start: { x: ball.x, y: ball.y } };
  if (state.selectedId !== ball.id) {
    state.selectedId = ball.id;
    for (const c of $('layer-balls').children) c.classList.toggle('selected', c.dataset.id === ball.id);
    $('remove-ball').disabled = false;
  }
}

function onBallPointerMove(event) {
  const d = state.drag;
  if (!d || event.pointerId !== d.pointerId) return;
  const p = toTable(event);
  if (!p) return;
  const q = clampToBed({ x: p.x + d.dx, y: p.y + d.dy });
  if (!d.moved && Math.hypot(q.x - d.start.x, q.y - d.start.y) < 0.002) return;
  if (!d.moved) {
    d.moved = true;
    $('layer-shot').classList.add('hidden');
    $('layer-paths').replaceChildren();
  }
  d.ball.x = q.x;
  d.ball.y = q.y;
  d.element.setAttribute('cx', q.x);
  d.element.setAttribute('cy', q.y);
}

function onBallPointerUp(event) {
  const d = state.drag;
  if (!d || event.pointerId !== d.pointerId) return;
  state.drag = null;
  d.element.classList.remove('dragging');
  if (d.element.hasPointerCapture(event.pointerId)) d.element.releasePointerCapture(event.pointerId);
  if (d.moved) {
    markCustomTable();
    drawBalls();
    plan('drop', event.timeStamp);
  }
}

function markCustomTable() { $('builtin').value = 'custom'; }

// ---------------------------------------------------------------------------
// Editing the table.

function setBalls(list) {
  state.balls = list.map((b) => ({ id: String(b.id), kind: String(b.kind), x: num(b.position.x), y: num(b.position.y) }));
  state.selectedId = null;
  drawBalls();
}

function freeSpotFor(kind) {
  const t = state.model.table;
  const R = state.radius;
  const clear = (p) => state.balls.every((b) => Math.hypot(b.x - p.x, b.y - p.y) >= 2 * R + 0.002);
  const spot = (t.spots || []).find((s) => s.kind === kind);
  if (spot && clear(vec(spot.position))) return vec(spot.position);
  const w = num(t.widthM), l = num(t.lengthM);
  const start = kind === 'CUE' ? { x: w / 2, y: num(t.baulkLineM) - num(t.dRadiusM) / 2 } : { x: w / 2, y: l / 2 };
  for (let ring = 0; ring < 60; ++ring) {
    const steps = Math.max(1, ring * 6);
    for (let k = 0; k < steps; ++k) {
      const a = (2 * Math.PI * k) / steps;
      const p = clampToBed({ x: start.x + ring * 2.5 * R * Math.cos(a), y: start.y + ring * 2.5 * R * Math.sin(a) });
      if (clear(p)) return p;
    }
  }
  return null;
}

function addBall() {
  if (!state.model) return;
  const kind = $('add-kind').value;
  let id;
  if (kind === 'CUE') {
    if (state.balls.some((b) => b.kind === 'CUE')) { showError('The table already has a cue ball.'); return; }
    id = 'cue';
  } else if (kind === 'RED') {
    let n = 1;
    while (state.balls.some((b) => b.id === `red-${n}`)) ++n;
    id = `red-${n}`;
  } else {
    if (state.balls.some((b) => b.kind === kind)) { showError(`The table already has the ${words(kind)}.`); return; }
    id = COLOUR_IDS[kind];
    if (state.balls.some((b) => b.id === id)) id = `${id}-2`;
  }
  const p = freeSpotFor(kind);
  if (!p) { showError('No free place for another ball.'); return; }
  endReplayView();
  state.balls.push({ id, kind, x: p.x, y: p.y });
  state.selectedId = id;
  markCustomTable();
  drawBalls();
  plan('edit');
}

function removeSelected() {
  const i = state.balls.findIndex((b) => b.id === state.selectedId);
  if (i < 0) return;
  endReplayView();
  state.balls.splice(i, 1);
  state.selectedId = null;
  markCustomTable();
  drawBalls();
  plan('edit');
}

function tableJson() {
  return { balls: state.balls.map((b) => ({ id: b.id, kind: b.kind, position: { x: b.x, y: b.y } })) };
}

function saveTable() {
  const blob = new Blob([JSON.stringify(tableJson(), null, 2) + '\n'], { type: 'application/json' });
  const url = URL.createObjectURL(blob);
  const a = html('a', { href: url, download: 'table.json' });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

// A table file's balls, or an Error saying what is wrong with its form (the server
// checks the rest: kinds, overlaps, balls off the table).
function parseTableFile(text, name) {
  let doc;
  try {
    doc = JSON.parse(text);
  } catch (e) {
    throw new Error(`${name} is not JSON: ${e.message}`);
  }
  if (!doc || !Array.isArray(doc.balls)) throw new Error(`${name} has no "balls" list (a table is {"balls": [{"id", "kind", "position": {"x", "y"}}]})`);
  return doc.balls.map((b, i) => {
    const where = `${name}: balls[${i}]${b && b.id ? ` ("${b.id}")` : ''}`;
    if (!b || typeof b !== 'object') throw new Error(`${where} is not an object`);
    if (typeof b.id !== 'string') throw new Error(`${where} has no "id" string`);
    if (typeof b.kind !== 'string') throw new Error(`${where} has no "kind" (CUE, RED, YELLOW, GREEN, BROWN, BLUE, PINK or BLACK)`);
    const p = b.position || {};
    for (const axis of ['x', 'y']) {
      if (typeof p[axis] !== 'number' || !Number.isFinite(p[axis])) throw new Error(`${where} has no number position.${axis}`);
    }
    return { id: b.id, kind: b.kind, position: { x: p.x, y: p.y } };
  });
}

async function loadTableFile(file) {
  if (!file) return;
  let balls;
  try {
    balls = parseTableFile(await file.text(), file.name);
  } catch (e) {
    abortPlan();
    showError(e.message);
    return;
  }
  endReplayView();
  setBalls(balls);
  if (balls.some((b) => b.kind === 'CUE')) $('cue-in-hand').checked = false;
  markCustomTable();
  plan('load');
}

// ---------------------------------------------------------------------------
// The plan request.

function readNumber(input) {
  const s = input.value.trim();
  if (s === '') return undefined;
  const v = Number(s);
  return Number.isFinite(v) ? v : undefined;
}

function applyNoisePreset(name) {
  const preset = NOISE_PRESETS[name];
  if (!preset) return;
  for (const input of document.querySelectorAll('[data-noise]')) input.value = String(preset[input.dataset.noise]);
}

function planRequest() {
  const inHand = cueInHand();
  const balls = state.balls
    .filter((b) => !(inHand && b.kind === 'CUE'))
    .map((b) => ({ id: b.id, kind: b.kind, position: { x: b.x, y: b.y } }));
  const noise = {};
  for (const input of document.querySelectorAll('[data-noise]')) {
    const v = readNumber(input);
    if (v !== undefined) noise[input.dataset.noise] = v;
  }
  const request = { table: { balls }, noise };
  const ballOn = $('ball-on').value;
  if (ballOn !== 'BALL_ON_UNSPECIFIED') request.ballOn = ballOn;
  const budget = readNumber($('budget'));
  if (budget !== undefined) request.timeBudgetMs = budget;
  const shots = readNumber($('max-shots'));
  if (shots !== undefined) request.maxShots = Math.round(shots);
  const simulations = readNumber($('max-simulations'));
  if (simulations !== undefined) request.maxSimulations = Math.round(simulations);
  const seed = readNumber($('seed'));
  if (seed !== undefined) request.seed = String(Math.round(seed));
  if (inHand) request.cueInHand = true;
  // Every kind (or route) ticked is the API's default, an empty list: sent only when
  // some are not.
  for (const [selector, field] of [['[data-kind]', 'kinds'], ['[data-route]', 'routes']]) {
    const boxes = [...document.querySelectorAll(selector)];
    const ticked = boxes.filter((b) => b.checked).map((b) => b.dataset.kind || b.dataset.route);
    if (ticked.length < boxes.length) request[field] = ticked;
  }
  if (!$('lookahead').checked) request.lookahead = false;
  if ($('thin-break-off').checked) request.thinBreakOff = true;
  const breakValue = readNumber($('break-value'));
  if (breakValue !== undefined) request.breakValue = breakValue;
  const positionSpread = readNumber($('position-spread'));
  if (positionSpread !== undefined) request.positionSpread = positionSpread;
  return request;
}

// A kind or route box changed: plan again, unless it was the last one ticked, which
// stays ticked (none would be the API's "every one").
function onChoiceChange(event, selector) {
  if (![...document.querySelectorAll(selector)].some((b) => b.checked)) {
    event.target.checked = true;
    return;
  }
  plan('options');
}

// ---------------------------------------------------------------------------
// Planning.

function abortPlan() {
  if (state.planController) state.planController.abort();
  state.planController = null;
}

async function plan(trigger, startMs) {
  if (!state.model) return;  // the page's first plan is asked for once the model is in
  abortPlan();
  abortReplay();
  endReplayView();
  clearError();
  const controller = new AbortController();
  state.planController = controller;
  const seq = ++state.planSeq;
  const request = planRequest();
  const balls = state.balls.map((b) => ({ ...b }));
  const start = startMs !== undefined ? startMs : performance.now();
  debugInfo.lastPlanRequest = request;
  document.body.dataset.planState = 'running';
  $('shots').tBodies[0].classList.add('stale');
  $('progress').textContent = 'Planning…';
  setStatus('Planning…');
  let progressCount = 0;
  const timing = { sentMs: performance.now(), answerMs: null };
  try {
    await callStream('PlanStream', request, controller.signal, (message) => {
      if (seq !== state.planSeq) return;
      if (!message.final) {
        ++progressCount;
        showProgress(message, balls, request);
      } else {
        timing.answerMs = performance.now();
        finishPlan(request, balls, message, { seq, trigger, start, progressCount, timing });
      }
    });
  } catch (e) {
    if (controller.signal.aborted || (e && e.name === 'AbortError') || seq !== state.planSeq) return;
    planFailed(e);
  } finally {
    if (state.planController === controller) state.planController = null;
  }
}

function planFailed(e) {
  showError(errorText(e));
  document.body.dataset.planState = 'error';
  setStatus('The plan failed.');
  $('progress').textContent = '';
  $('shots').tBodies[0].replaceChildren();
  $('shots').tBodies[0].classList.remove('stale');
  $('reason').hidden = true;
  $('layer-shot').replaceChildren();
  $('layer-paths').replaceChildren();
  $('detail').hidden = true;
  state.planned = null;
  state.selectedShot = -1;
  resetReplayControls();
}

// "pot, direct" in sentences; in the list a pot is named by its route alone. A foul
// (the last resort when no legal stroke exists) names the colour it nominates.
// The position a shot leaves, after the cue ball's place: ours after a pot, the
// opponent's after a safety, escape or break-off (their position is the planner's
// estimate of the table they get); a foul's is not scored so.
function leaveWords(shot) {
  if (shot.kind === 'FOUL') return '';
  const whose = shot.kind === 'POT' ? 'position' : 'the opponent\'s position';
  return `, ${whose} ${fixed(shot.positionValue, 2)}`;
}

// What a stroke that hands the table over leaves the opponent (the answer's
// `opponent`): their best pot and expected points, and whether they are snookered.
function opponentWords(o) {
  const pot = `best pot ${pct(o.potProbability)}, ${fixed(o.expectedPoints, 1)} points expected`;
  return o.snookered
    ? `${pot}; snookered: ${pct(o.foulProbability)} to miss, a ${fixed(o.penaltyPoints, 0)}-point foul`
    : pot;
}

// What the Monte Carlo's runs that handed the table over left the opponent (the
// answer's `handovers`): how many runs, their best pot and expected points on
// average, and how many left them snookered; '' when no run handed it over.
function handoverWords(shot) {
  const h = shot.handovers;
  if (!h || num(h.runs) === 0) return '';
  return `in ${num(h.runs)} of ${num(shot.monteCarloSamples)} runs: their best pot ${pct(h.meanPotProbability)}, ` +
    `${fixed(h.meanExpectedPoints, 1)} points on average; snookered in ${num(h.snookeredRuns)}`;
}

// A foul names its object ball as a nomination only when it is a colour: with a red
// on there is nothing to nominate, and the object ball is the red played.
function shotLabel(shot, balls, short) {
  const kind = shot.kind || 'SHOT_KIND_UNSPECIFIED';
  if (kind === 'POT') return (short ? '' : 'pot, ') + words(shot.route || 'direct');
  const object = kind === 'FOUL' && (balls || []).find((b) => b.id === shot.objectBall);
  if (object && object.kind !== 'RED' && object.kind !== 'CUE') return `foul, nominating ${shot.objectBall}`;
  return words(kind);
}

function showProgress(message, balls, request) {
  const shot = (message.shots || [])[0];
  showWarnings(message.warnings);
  if (!shot) return;
  const target = shot.pocket ? `${shot.objectBall} → ${shot.pocket}` : shot.objectBall || 'no ball';
  $('progress').textContent = `Best so far (${fixed(message.elapsedMs, 0)} ms): ${shotLabel(shot, balls)}, ${target}, ` +
    `P(pot) ≈ ${pct(shot.potProbability)} (fast estimate)`;
  drawShot(shot, balls, request, null, true);
  ++debugInfo.progressShown;
}

function finishPlan(request, balls, response, info) {
  state.planned = { request, balls, response };
  showWarnings(response.warnings);
  renderShots(response, balls);
  const n = (response.shots || []).length;
  // The work, and whether the clock cut it short (then another run may differ).
  const work = `${num(response.simulations)} of ${num(response.simulationCap)} simulations` +
    (response.cutShort ? ', cut short' : '');
  $('progress').textContent = n
    ? `${n} shot${n > 1 ? 's' : ''} in ${fixed(response.elapsedMs, 0)} ms (${work})`
    : '';
  if (n) {
    selectShot(0);
  } else {
    state.selectedShot = -1;
    abortReplay();
    $('layer-shot').replaceChildren();
    $('layer-paths').replaceChildren();
    $('detail').hidden = true;
    resetReplayControls();
  }
  // The plan is on the page: the list, the best shot drawn and described.
  const end = performance.now();
  setStatus(`Planned in ${Math.round(end - info.start)} ms.`);
  debugInfo.lastPlanResponse = response;
  debugInfo.lastPlan = {
    seq: info.seq, trigger: info.trigger, startMs: info.start, endMs: end, ms: end - info.start,
    serverMs: num(response.elapsedMs), progressMessages: info.progressCount, shots: n,
    sentMs: info.timing.sentMs, answerMs: info.timing.answerMs,
  };
  if (!state.firstPlanDone) {
    state.firstPlanDone = true;
    debugInfo.firstPlanMs = end;
  }
  debugInfo.planSeq = info.seq;
  document.body.dataset.planState = 'done';
  document.body.dataset.planSeq = String(info.seq);
}

// How many Monte Carlo runs the probabilities and the points count.
const runsWords = (shot) => (num(shot.monteCarloSamples) > 0 ? ` (${num(shot.monteCarloSamples)} runs)` : ' (its nominal run)');

function renderShots(response, balls) {
  const body = $('shots').tBodies[0];
  body.classList.remove('stale');
  body.replaceChildren();
  const shots = response.shots || [];
  shots.forEach((shot, i) => {
    const target = html('td', { class: 'target' });
    target.append(ballLabel(shot.objectBall, balls));
    if (shot.pocket) target.append(' → ' + shot.pocket);
    if (shot.route === 'PLANT' && shot.firstBall) target.append(' (off ', ballLabel(shot.firstBall, balls), ')');
    const row = html('tr', { 'data-index': String(i) }, [
      html('td', { text: String(i + 1) }),
      html('td', { text: shotLabel(shot, balls, true), title: shotLabel(shot, balls) }),
      target,
      html('td', { class: 'num pot', text: pct(shot.potProbability), 'data-value': String(num(shot.potProbability)) }),
      html('td', { class: 'num foul', text: pct(shot.foulProbability), 'data-value': String(num(shot.foulProbability)) }),
      html('td', { class: 'num pts', text: fixed(shot.expectedPoints, 1), 'data-value': String(num(shot.expectedPoints)) }),
      html('td', shot.kind === 'POT'
        ? { class: 'num pos', text: fixed(shot.positionValue, 2) }
        : { class: 'num pos theirs', text: fixed(shot.positionValue, 2),
          title: 'the opponent\'s position: what the table left offers them (low is good)' }),
      html('td', {}, [ballLabel(shot.nextBall, balls)]),
    ]);
    row.addEventListener('click', () => selectShot(i));
    body.append(row);
  });
  const reason = $('reason');
  reason.hidden = shots.length > 0;
  reason.textContent = shots.length ? '' : `No shot: ${response.reason || 'the planner found none'}.`;
}

// The cue ball's start for a shot: where it is placed from hand, or where it lies.
function cueStart(shot, balls) {
  if (shot.cueBallStart) return vec(shot.cueBallStart);
  const cue = balls.find((b) => b.kind === 'CUE');
  return cue ? { x: cue.x, y: cue.y } : null;
}

// Draws a shot's aim on the table: the cue, the ghost ball where the cue ball meets
// the first ball, the aim point (their contact) and where the cue ball stops. With
// `contact` (from the shot's simulation) the ghost ball is exact; without it, it is
// the straight-line one, drawn only for a direct pot.
function drawShot(shot, balls, request, contact, provisional) {
  const g = $('layer-shot');
  g.replaceChildren();
  g.classList.remove('hidden');
  const R = state.radius;
  const start = cueStart(shot, balls);
  if (!start) return;
  const cue = shot.cue || {};
  const h = (num(cue.headingDeg !== undefined ? cue.headingDeg : shot.headingDeg) * Math.PI) / 180;
  // The cue, behind the cue ball along its heading.
  const back = { x: -Math.cos(h), y: -Math.sin(h) };
  svg('line', {
    class: 'cue-stick', x1: start.x + back.x * (R + 0.02), y1: start.y + back.y * (R + 0.02),
    x2: start.x + back.x * (R + 0.6), y2: start.y + back.y * (R + 0.6),
  }, g);
  if (shot.cueBallStart) svg('circle', { class: 'ghost', cx: start.x, cy: start.y, r: R }, g);
  let ghost = contact ? contact.ghost : null;
  let aim = contact ? contact.aim : null;
  if (!ghost && (shot.route === 'DIRECT' || !shot.route) && shot.kind === 'POT') {
    const object = balls.find((b) => b.id === (shot.firstBall || shot.objectBall));
    if (object) {
      const dep = ((num(shot.headingDeg) + num(shot.cutDeg)) * Math.PI) / 180;
      ghost = { x: object.x - 2 * R * Math.cos(dep), y: object.y - 2 * R * Math.sin(dep) };
      aim = { x: object.x - R * Math.cos(dep), y: object.y - R * Math.sin(dep) };
    }
  }
  if (ghost) {
    if (!contact || contact.straight) {
      svg('line', { class: provisional ? 'aim-line progress-shot' : 'aim-line', x1: start.x, y1: start.y, x2: ghost.x, y2: ghost.y }, g);
    }
    svg('circle', { class: 'ghost', cx: ghost.x, cy: ghost.y, r: R }, g);
    svg('title', {}, svg('circle', { class: 'aim-point', cx: aim.x, cy: aim.y, r: 0.007 }, g)).textContent = 'aim point (contact)';
  } else {
    svg('line', { class: 'aim-line', x1: start.x, y1: start.y, x2: start.x + Math.cos(h) * 0.4, y2: start.y + Math.sin(h) * 0.4 }, g);
  }
  if (!provisional && shot.cueBallEnd) {
    const e = vec(shot.cueBallEnd);
    svg('title', {}, svg('circle', { class: 'end-marker', cx: e.x, cy: e.y, r: R * 1.15 }, g)).textContent = 'where the cue ball stops';
  }
}

function selectShot(i) {
  const planned = state.planned;
  if (!planned || !planned.response.shots || !planned.response.shots[i]) return;
  state.selectedShot = i;
  const shot = planned.response.shots[i];
  for (const row of $('shots').tBodies[0].rows) row.classList.toggle('selected', row.dataset.index === String(i));
  endReplayView();
  $('layer-paths').replaceChildren();
  drawShot(shot, planned.balls, planned.request, null, false);
  showDetail(shot, planned);
  loadReplay(i);
}

function showDetail(shot, planned) {
  const balls = planned.balls;
  $('detail').hidden = false;
  const target = shot.pocket ? `${shot.objectBall} into ${shot.pocket}` : shot.objectBall || 'no ball';
  $('detail-title').textContent = `Shot ${state.selectedShot + 1}: ${shotLabel(shot, balls)}, ${target}`;
  const cue = shot.cue || {};
  const side = num(cue.tipSide), height = num(cue.tipHeight), elevation = num(cue.elevationDeg);
  const dot = $('tip-dot');
  dot.setAttribute('cx', side);
  dot.setAttribute('cy', -height);
  const limit = state.model && state.model.cue ? num(state.model.cue.miscueLimit) : 0;
  $('tip-limit').setAttribute('r', limit > 0 ? limit : 0.6);
  const e = (elevation * Math.PI) / 180;
  const line = $('elevation-cue');
  line.setAttribute('x1', 0.35 * Math.cos(e) + 0.05);
  line.setAttribute('y1', -0.35 - 0.35 * Math.sin(e));
  line.setAttribute('x2', 0.35 * Math.cos(e) + 0.05 + 1.6 * Math.cos(e));
  line.setAttribute('y2', -0.35 - 0.35 * Math.sin(e) - 1.6 * Math.sin(e));
  $('elevation-caption').textContent = `elevation ${elevation.toFixed(1)}°`;
  const side_ = side === 0 ? 'centre' : `${Math.abs(side).toFixed(2)} R ${side > 0 ? 'right' : 'left'}`;
  const height_ = height === 0 ? 'centre' : `${Math.abs(height).toFixed(2)} R ${height > 0 ? 'above' : 'below'}`;
  const end = vec(shot.cueBallEnd);
  const rows = [
    ['aim', `${fixed(cue.headingDeg, 2)}° (the cue's heading, squirt allowed for)`],
    ['cue speed', `${fixed(cue.speed, 2)} m/s`],
    ['tip', side === 0 && height === 0 ? 'centre ball' : `${side_}, ${height_}`],
    ['elevation', `${elevation.toFixed(1)}°`],
    ['cue ball', `${fixed(shot.speed, 2)} m/s at ${fixed(shot.headingDeg, 2)}°, cut ${fixed(shot.cutDeg, 1)}°`],
    ...(shot.kind === 'POT' ? [['P(pot)', `${pct(shot.potProbability)} (this pocket ${pct(shot.pocketProbability)})`]] : []),
    ['P(foul)', pct(shot.foulProbability)],
    ['worth', `${fixed(shot.expectedPoints, 1)} points to the striker` + runsWords(shot)],
    ['leaves', `the cue ball at (${end.x.toFixed(3)}, ${end.y.toFixed(3)}) m` + leaveWords(shot)],
  ];
  if (shot.kind === 'POT') rows.push(['next ball', ballLabel(shot.nextBall, balls)]);
  else if (shot.kind !== 'FOUL') rows.push(['their best ball', ballLabel(shot.nextBall, balls)]);
  if (shot.opponent) rows.push(['for them', opponentWords(shot.opponent)]);
  const handedOver = handoverWords(shot);
  if (handedOver) rows.push(['handed over', handedOver]);
  if (shot.cueBallStart) {
    const s = vec(shot.cueBallStart);
    rows.unshift(['place cue ball', `(${s.x.toFixed(3)}, ${s.y.toFixed(3)}) m`]);
  }
  if (shot.route === 'PLANT' && shot.firstBall) rows.splice(1, 0, ['first ball', ballLabel(shot.firstBall, balls)]);
  $('detail-list').replaceChildren(...rows.flatMap(([k, v]) => [html('dt', { text: k }), html('dd', {}, [v])]));
}

// ---------------------------------------------------------------------------
// Replay.

function abortReplay() {
  if (state.replayController) state.replayController.abort();
  state.replayController = null;
  stopPlaying();
  state.replay = null;
}

function resetReplayControls() {
  $('play').disabled = true;
  $('play').textContent = 'Play';
  const s = $('scrubber');
  s.disabled = true;
  s.value = '0';
  $('replay-time').textContent = 'no replay';
}

async function loadReplay(shotIndex) {
  abortReplay();
  resetReplayControls();
  const planned = state.planned;
  const shot = planned.response.shots[shotIndex];
  const balls = planned.request.table.balls.map((b) => ({ ...b }));
  if (shot.cueBallStart) balls.push({ id: PLACED_CUE_ID, kind: 'CUE', position: vec(shot.cueBallStart) });
  const request = {
    table: { balls },
    shot: {
      speed: num(shot.speed), headingDeg: num(shot.headingDeg), topspin: num(shot.topspin),
      sidespin: num(shot.sidespin), swerveSpin: num(shot.swerveSpin),
    },
    options: { includePaths: true },
  };
  const controller = new AbortController();
  state.replayController = controller;
  $('replay-time').textContent = 'simulating…';
  let answer;
  try {
    answer = await callUnary('Simulate', request, controller.signal);
  } catch (e) {
    if (controller.signal.aborted || (e && e.name === 'AbortError')) return;
    $('replay-time').textContent = 'no replay';
    showError('Replay: ' + errorText(e));
    return;
  }
  if (state.replayController !== controller) return;
  state.replayController = null;
  const kinds = new Map(balls.map((b) => [b.id, b.kind]));
  const paths = (answer.paths || []).filter((p) => (p.points || []).length > 0);
  const pocketed = new Set((answer.finalBalls || []).filter((f) => f.pocketed).map((f) => f.id));
  let duration = num(answer.durationS);
  for (const p of paths) duration = Math.max(duration, num(p.t[p.t.length - 1]));
  state.replay = { shotIndex, paths, kinds, pocketed, balls, duration, t: 0, playing: false, last: 0 };
  ++debugInfo.replaySeq;
  drawPaths(paths, kinds);
  const contact = firstContact(answer.events || [], paths, shot);
  drawShot(shot, planned.balls, planned.request, contact, false);
  $('play').disabled = false;
  $('scrubber').disabled = false;
  showReplayTime();
}

function drawPaths(paths, kinds) {
  const g = $('layer-paths');
  g.replaceChildren();
  for (const p of paths) {
    if (p.points.length < 2) continue;
    const first = vec(p.points[0]), last = vec(p.points[p.points.length - 1]);
    if (Math.hypot(first.x - last.x, first.y - last.y) < 1e-4 && p.points.length < 3) continue;
    svg('polyline', {
      class: 'path ' + kindClass(kinds.get(p.id)),
      points: p.points.map((q) => `${num(q.x).toFixed(4)},${num(q.y).toFixed(4)}`).join(' '),
    }, g);
  }
}

// Where the cue ball first meets another ball in the simulation: the ghost ball
// (the cue ball's centre then) and the aim point (the contact, halfway to the other
// centre).
function firstContact(events, paths, shot) {
  const cueId = shot.cueBallStart ? PLACED_CUE_ID : null;
  const byId = new Map(paths.map((p) => [p.id, p]));
  const isCue = (id) => (cueId ? id === cueId : state.replay && state.replay.kinds.get(id) === 'CUE');
  let straight = true;  // no cushion on the way
  for (const e of events) {
    const ids = e.balls || [];
    const cue = ids.find(isCue);
    if (!cue) continue;
    if (e.kind === 'CUSHION' || e.kind === 'JAW_WALL' || e.kind === 'KNUCKLE') straight = false;
    if (e.kind !== 'BALL_BALL') continue;
    const other = ids.find((id) => id !== cue);
    if (!other || !byId.has(cue) || !byId.has(other)) return null;
    const t = num(e.time);
    const ghost = pointAt(byId.get(cue), t);
    const o = pointAt(byId.get(other), t);
    return { ghost, aim: { x: (ghost.x + o.x) / 2, y: (ghost.y + o.y) / 2 }, straight };
  }
  return null;
}

function showReplayTime() {
  const r = state.replay;
  if (!r) return;
  $('replay-time').textContent = `${r.t.toFixed(2)} s of ${r.duration.toFixed(2)} s`;
  $('scrubber').value = String(r.duration > 0 ? Math.round((1000 * r.t) / r.duration) : 0);
}

function drawReplayAt(t) {
  const r = state.replay;
  const g = $('layer-replay');
  g.replaceChildren();
  const byId = new Map(r.paths.map((p) => [p.id, p]));
  for (const b of r.balls) {
    const path = byId.get(b.id);
    let p = path ? pointAt(path, t) : vec(b.position);
    if (path && r.pocketed.has(b.id) && t >= num(path.t[path.t.length - 1])) p = null;
    if (!p) continue;
    svg('circle', { class: 'replay-ball ' + kindClass(b.kind), cx: p.x, cy: p.y, r: state.radius, 'data-id': b.id }, g);
  }
}

function beginReplayView() {
  if (state.replayActive) return;
  state.replayActive = true;
  $('layer-balls').classList.add('hidden');
  $('layer-shot').classList.add('hidden');
}

function endReplayView() {
  stopPlaying();
  if (state.replay) {
    state.replay.t = 0;
    showReplayTime();
  }
  if (!state.replayActive) return;
  state.replayActive = false;
  $('layer-replay').replaceChildren();
  $('layer-balls').classList.remove('hidden');
  $('layer-shot').classList.remove('hidden');
}

function stopPlaying() {
  const r = state.replay;
  if (r && r.playing) {
    r.playing = false;
    if (r.frame) cancelAnimationFrame(r.frame);
  }
  $('play').textContent = 'Play';
}

function togglePlay() {
  const r = state.replay;
  if (!r) return;
  if (r.playing) { stopPlaying(); return; }
  if (r.t >= r.duration) r.t = 0;
  beginReplayView();
  r.playing = true;
  r.last = performance.now();
  $('play').textContent = 'Pause';
  const step = (now) => {
    if (!r.playing || state.replay !== r) return;
    const speed = Number($('replay-speed').value) || 1;
    r.t = Math.min(r.duration, r.t + ((now - r.last) / 1000) * speed);
    r.last = now;
    drawReplayAt(r.t);
    showReplayTime();
    if (r.t >= r.duration) { stopPlaying(); return; }
    r.frame = requestAnimationFrame(step);
  };
  drawReplayAt(r.t);
  r.frame = requestAnimationFrame(step);
}

function scrub() {
  const r = state.replay;
  if (!r) return;
  stopPlaying();
  beginReplayView();
  r.t = (Number($('scrubber').value) / 1000) * r.duration;
  drawReplayAt(r.t);
  $('replay-time').textContent = `${r.t.toFixed(2)} s of ${r.duration.toFixed(2)} s`;
}

// ---------------------------------------------------------------------------
// Start.

// The built-in tables come from GetModel (the planner's, as `snooker plan --table
// builtin:NAME` plays them): the menu lists them before "(your table)", and the first,
// the demonstration's, is drawn and planned on load.
function useBuiltinTables(tables) {
  const select = $('builtin');
  const custom = select.querySelector('option[value="custom"]');
  for (const t of tables) {
    state.builtinTables[t.name] = (t.state && t.state.balls) || [];
    const option = document.createElement('option');
    option.value = t.name;
    option.textContent = `${t.name}: ${t.description}`;
    select.insertBefore(option, custom);
  }
  debugInfo.builtinTables = state.builtinTables;
  if (tables.length) {
    select.value = tables[0].name;
    setBuiltin(tables[0].name);
  }
}

// Puts built-in table `name` on the page; a table without a cue ball has it in hand.
function setBuiltin(name) {
  const balls = state.builtinTables[name];
  if (!balls) return false;
  $('cue-in-hand').checked = !balls.some((b) => b.kind === 'CUE');
  setBalls(balls);
  return true;
}

function start() {
  applyNoisePreset('robot');

  const modelReady = callUnary('GetModel', {}).then((model) => {
    state.model = model;
    state.radius = num(model.ball && model.ball.radiusM) || state.radius;
    drawTable();
    useBuiltinTables(model.builtinTables || []);
    const build = model.build || {};
    if (build.version) $('build').textContent = `server ${build.version}, commit ${build.commit}`;
    const s = model.service || {};
    const budget = $('budget');
    budget.placeholder = String(num(s.defaultPlanBudgetMs));
    budget.title = `empty: the server's default, ${num(s.defaultPlanBudgetMs)} ms`;
    if (s.maxPlanBudgetMs) budget.max = String(num(s.maxPlanBudgetMs));
    setStatus('Ready.');
    plan('load');
  });
  modelReady.catch((e) => {
    showError('Cannot load the table model: ' + errorText(e));
    setStatus('No model.');
  });

  const table = $('table');
  table.addEventListener('pointerdown', (event) => {
    if (event.target.closest('circle.ball')) onBallPointerDown(event);
    else endReplayView();
  });
  table.addEventListener('pointermove', onBallPointerMove);
  table.addEventListener('pointerup', onBallPointerUp);
  table.addEventListener('pointercancel', onBallPointerUp);

  $('builtin').addEventListener('change', () => {
    if (setBuiltin($('builtin').value)) plan('table');
  });
  $('add-ball').addEventListener('click', addBall);
  $('remove-ball').addEventListener('click', removeSelected);
  document.addEventListener('keydown', (event) => {
    if ((event.key === 'Delete' || event.key === 'Backspace') && !event.target.closest('input, select, textarea')) {
      if (state.selectedId) { event.preventDefault(); removeSelected(); }
    }
  });
  $('load-file').addEventListener('change', (event) => {
    loadTableFile(event.target.files[0]);
    event.target.value = '';
  });
  $('save-file').addEventListener('click', saveTable);
  $('cue-in-hand').addEventListener('change', () => { drawBalls(); plan('options'); });
  $('ball-on').addEventListener('change', () => plan('options'));
  for (const selector of ['[data-kind]', '[data-route]']) {
    for (const box of document.querySelectorAll(selector)) {
      box.addEventListener('change', (event) => onChoiceChange(event, selector));
    }
  }
  $('lookahead').addEventListener('change', () => plan('options'));
  $('thin-break-off').addEventListener('change', () => plan('options'));
  $('break-value').addEventListener('change', () => plan('options'));
  $('position-spread').addEventListener('change', () => plan('options'));
  $('noise-preset').addEventListener('change', () => {
    applyNoisePreset($('noise-preset').value);
    plan('options');
  });
  for (const input of document.querySelectorAll('[data-noise]')) {
    input.addEventListener('input', () => { $('noise-preset').value = 'custom'; });
  }
  $('plan-form').addEventListener('submit', (event) => {
    event.preventDefault();
    plan('button');
  });
  $('play').addEventListener('click', togglePlay);
  $('scrubber').addEventListener('input', scrub);
}

start();
