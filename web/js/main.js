// The viewer: scene list and controls over REST, frames and control over the
// scene's WebSocket, decoding in a Web Worker, drawing with WebGL2.

import { OrbitCamera, perspective } from './camera.js';
import { Credentials } from './credentials.js';
import { wallLines } from './outline.js';
import { Renderer } from './render.js';

const $ = (id) => document.getElementById(id);
const credentials = new Credentials(sessionStorage);
const askedScene = credentials.readFragment(location, history);
const api = (path, init) => fetch(`/api/v1${path}`, {
  headers: { 'content-type': 'application/json', ...credentials.headers() }, ...init,
}).then(async (r) => {
  const body = await r.json().catch(() => ({}));
  const why = body.error ?? `${r.status} ${r.statusText}`;
  if (r.status === 401) throw new Error(`${why} Open this page as ${location.origin}/#token=YOUR_TOKEN`);
  if (!r.ok) throw new Error(why);
  return body;
});

const canvas = $('view');
const renderer = new Renderer(canvas);
const camera = new OrbitCamera(canvas);
const worker = new Worker(new URL('./codec/worker.js', import.meta.url), { type: 'module' });

const state = {
  scene: null, socket: null, wantOpen: false, running: false,
  frames: 0, bytes: 0, lastBytes: 0, decodeMs: 0, renderFps: 0, lastStatus: null,
};

function banner(text) {
  $('banner').hidden = !text;
  $('banner').textContent = text ?? '';
}

function rtf() {
  const v = 10 ** Number($('rtf').value);
  $('rtf-value').textContent = v >= 1 ? v.toFixed(1) : v.toPrecision(2);
  return v;
}

/** The channel the colour mode needs (only that one is streamed). */
function channelFor(mode) {
  return { speed: 'velocity', density: 'density', pressure: 'pressure' }[mode] ?? '';
}

/**
 * Re-reads the scene list and opens `select`, else the scene shown now if it is
 * still there, else the first. `reopen` opens it afresh even if it is the one
 * shown (after a reconnect the server may have restarted under the page).
 */
async function refreshScenes(select, reopen = false) {
  const scenes = await api('/scenes');
  const sel = $('scenes');
  sel.replaceChildren(...scenes.map((s) => new Option(`${s.scene_id}: ${s.name} (${s.particles} particles)`, s.scene_id)));
  const known = (i) => scenes.some((s) => s.scene_id === i);
  const id = [select, state.scene?.scene_id].find(known) ?? scenes[0]?.scene_id;
  if (id != null) {
    sel.value = id;
    if (reopen || id !== state.scene?.scene_id) open(scenes.find((s) => s.scene_id === Number(id)));
  } else {
    close();
    state.scene = null;
  }
}

function close() {
  state.wantOpen = false;
  state.socket?.close();
  state.socket = null;
}

function open(scene) {
  close();
  state.scene = scene;
  state.wantOpen = true;
  banner(scene.halt_reason ? `Halted: ${scene.halt_reason}` : null);
  camera.fit(scene.bounds_min, scene.bounds_max);
  renderer.radius = 0.5 * scene.particle_spacing;
  renderer.outline.set(wallLines(scene.scene));
  connect();
}

function connect() {
  if (!state.wantOpen || !state.scene) return;
  const channel = channelFor($('colour').value);
  const url = new URL(`/api/v1/scenes/${state.scene.scene_id}/ws`, location.href);
  url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
  url.search = new URLSearchParams({ channels: channel, max_fps: '60' });
  const ws = new WebSocket(url, credentials.protocols());
  ws.binaryType = 'arraybuffer';
  state.socket = ws;
  ws.onmessage = (e) => {
    if (typeof e.data === 'string') return onText(JSON.parse(e.data));
    state.bytes += e.data.byteLength;
    state.lastBytes = e.data.byteLength;
    worker.postMessage({ bytes: e.data }, [e.data]);
  };
  ws.onclose = () => {
    if (state.socket !== ws || !state.wantOpen) return;
    // The server went away or restarted: find it again, then the scene.
    setTimeout(reconnect, 1000);
  };
}

/** Re-reads the scene list every second until the server answers, then reopens the scene. */
function reconnect() {
  refreshScenes(undefined, true).catch(() => setTimeout(reconnect, 1000));
}

function onText(msg) {
  if (msg.type === 'status') {
    if (!['gravity', 'xsph'].includes(document.activeElement?.id)) showSettings(msg.scene.scene);
    state.lastStatus = msg.scene;
    // A halt banner goes once the scene is no longer halted (after a reset).
    if (msg.scene.state !== 'halted' && $('banner').textContent.startsWith('Halted')) banner(null);
    state.running = msg.scene.state === 'running';
    if (msg.scene.state === 'halted') banner(`Halted: ${msg.scene.halt_reason}`);
  } else if (msg.type === 'event' && msg.event === 'halted') {
    state.running = false;
    banner(`Halted: ${msg.reason}`);
  } else if (msg.type === 'event' && msg.event === 'parameter_changed') {
    send({ op: 'status' });
    $('param').value = '';
    $('param').placeholder = `applied: ${msg.overrides.join(' ')}`;
  } else if (msg.type === 'event' && msg.event === 'deleted') {
    // Deleted by someone, or the server is shutting down: find what is there now.
    reconnect();
  } else if (msg.type === 'error') {
    banner(msg.message);
    setTimeout(() => banner(state.lastStatus?.halt_reason ? `Halted: ${state.lastStatus.halt_reason}` : null), 4000);
  }
}

worker.onmessage = ({ data }) => {
  if (data.error) return banner(`Frame could not be decoded: ${data.error.message}`);
  state.frames += 1;
  state.decodeMs = data.decodeMs ?? 0;
  const mode = $('colour').value;
  let values = null;
  if (mode === 'speed' && data.velocities) {
    const v = data.velocities;
    values = new Float32Array(v.length / 3);
    for (let i = 0; i < values.length; i++) values[i] = Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  } else if (mode === 'density' && data.densities) values = data.densities;
  else if (mode === 'pressure' && data.pressures) values = data.pressures;
  if (values) {
    let lo = Infinity, hi = -Infinity;
    for (const x of values) { if (x < lo) lo = x; if (x > hi) hi = x; }
    renderer.range = [lo, hi];
    $('legend-min').textContent = lo.toPrecision(3);
    $('legend-max').textContent = hi.toPrecision(3);
  }
  renderer.upload(data.positions, values);
};

function send(op) {
  if (state.socket?.readyState === WebSocket.OPEN) state.socket.send(JSON.stringify(op));
}

$('play').onclick = () => send({ op: 'run', real_time_factor: rtf() });
$('pause').onclick = () => send({ op: 'pause' });
$('step').onclick = () => send({ op: 'step', steps: 1 });
$('reset').onclick = () => { banner(null); send({ op: 'reset' }); };
// Sliders for tunable settings: applied when released.
$('gravity').oninput = () => { $('gravity-value').textContent = Number($('gravity').value).toFixed(2); };
$('gravity').onchange = () => send({ op: 'set', overrides: [`gravity=[0,${$('gravity').value},0]`] });
$('xsph').oninput = () => { $('xsph-value').textContent = Number($('xsph').value).toFixed(2); };
$('xsph').onchange = () => send({ op: 'set', overrides: [`fluids[0].xsph=${$('xsph').value}`] });

/** Shows a scene's current tunable settings on the sliders. */
function showSettings(scene) {
  const g = scene?.gravity?.[1];
  if (typeof g === 'number') { $('gravity').value = g; $('gravity-value').textContent = g.toFixed(2); }
  const x = scene?.fluids?.[0]?.xsph;
  if (typeof x === 'number') { $('xsph').value = x; $('xsph-value').textContent = x.toFixed(2); }
}
$('rtf').oninput = () => { const v = rtf(); if (state.running) send({ op: 'run', real_time_factor: v }); };
$('colour').onchange = () => { if (state.scene) open(state.scene); };
$('scenes').onchange = () => refreshScenes(Number($('scenes').value));
$('apply').onclick = () => {
  const text = $('param').value.trim();
  if (text) send({ op: 'set', overrides: text.split(/\s+/) });
};
$('delete').onclick = async () => {
  if (!state.scene) return;
  close();
  await api(`/scenes/${state.scene.scene_id}`, { method: 'DELETE' }).catch((e) => banner(e.message));
  state.scene = null;
  refreshScenes();
};
async function create(body) {
  try {
    const scene = await api('/scenes', { method: 'POST', body: JSON.stringify(body) });
    await refreshScenes(scene.scene_id);
    banner(null);
  } catch (e) {
    banner(e.message);
  }
}
$('create').onclick = () => create({ preset: $('preset').value });
$('create-doc').onclick = () => {
  const text = $('document').value;
  create({ document: text, document_format: text.trim().startsWith('{') ? 'json' : 'toml' });
};
$('file').onchange = async () => { $('document').value = await $('file').files[0].text(); };
addEventListener('keydown', (e) => {
  if (e.target.tagName === 'TEXTAREA' || (e.target.tagName === 'INPUT' && e.target.type === 'text')) return;
  if (e.key === ' ') { e.preventDefault(); send(state.running ? { op: 'pause' } : { op: 'run', real_time_factor: rtf() }); }
  if (e.key === 's') send({ op: 'step', steps: 1 });
  if (e.key === 'r') send({ op: 'reset' });
});

// Colour-map legend, drawn once.
{
  const g = $('legend-bar').getContext('2d'), grad = g.createLinearGradient(0, 0, 200, 0);
  grad.addColorStop(0, 'rgb(68,1,84)'); grad.addColorStop(0.5, 'rgb(33,145,140)'); grad.addColorStop(1, 'rgb(253,231,37)');
  g.fillStyle = grad;
  g.fillRect(0, 0, 200, 10);
}

// Render loop and stats overlay.
let fpsFrames = 0, fpsStart = performance.now();
function frame(now) {
  const aspect = canvas.clientWidth / Math.max(canvas.clientHeight, 1);
  renderer.draw(perspective(0.8, aspect, 0.01, 100), camera.view());
  fpsFrames += 1;
  if (now - fpsStart > 1000) {
    state.renderFps = (fpsFrames * 1000) / (now - fpsStart);
    fpsFrames = 0;
    fpsStart = now;
    send({ op: 'status' });
    const s = state.lastStatus;
    $('stats').textContent = [
      `render     ${state.renderFps.toFixed(0)} fps`,
      `particles  ${renderer.count}${s ? ` on ${s.backend}` : ''}`,
      s ? `sim time   ${s.sim_time.toFixed(3)} s (${s.state})` : '',
      s ? `steps/s    ${s.steps_per_second.toFixed(0)}` : '',
      `frames     ${state.frames}`,
      `bytes/frm  ${state.lastBytes} (${(state.lastBytes / Math.max(renderer.count, 1)).toFixed(2)} B/particle)`,
      `decode     ${state.decodeMs.toFixed(2)} ms`,
      s ? `dropped    ${s.dropped_frames}` : '',
    ].filter(Boolean).join('\n');
  }
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

rtf();
api('/presets').then((p) => $('preset').replaceChildren(...p.map((n) => new Option(n, n)))).catch((e) => banner(e.message));
refreshScenes(askedScene).catch((e) => banner(`Cannot reach the server: ${e.message}`));
