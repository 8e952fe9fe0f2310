// The viewer: scene list and controls over REST, frames and events over the scene's WebSocket,
// decoding in a Web Worker, drawing with WebGL2; plots, recording and replay in their modules.

import { OrbitCamera } from './camera.js';
import { DEFAULT_CHANNELS, NONE, colourModes, colourValues, valueRange } from './colour.js';
import { Credentials } from './credentials.js';
import { orientationValues, orientedRadii, streamedChannels } from './ellipsoid.js';
import { bindKeys, fillHelp } from './help.js';
import { LOOKS, lookChannels, lookValues, sceneLooks } from './looks.js';
import { acting, showError } from './notify.js';
import { wallLines } from './outline.js';
import { PlotPanel } from './plots.js';
import { Recorder } from './recorder.js';
import { realTime, statsText } from './overlay.js';
import { Renderer } from './render.js';
import { Replay } from './replay.js';
import { Routes } from './route.js';
import { FPS as OTHER_FPS, OtherSets } from './sets.js';
import { SettingsPanel } from './settings.js';
import { fullSizeLabel, fullSizeRequest } from './sizing.js';
import { BUDGET, ViewSync } from './view.js';

const $ = (id) => document.getElementById(id);
const credentials = new Credentials(sessionStorage);
const askedScene = credentials.readFragment(location, history);
// In a cluster, each scene's worker (js/route.js); on a single server every path stays /api/v1.
const routes = new Routes();
const api = (path, init) => routes.fetch(fetch, path, {
  headers: { 'content-type': 'application/json', ...credentials.headers() }, ...init,
}).then(async (r) => {
  const body = await r.json().catch(() => ({}));
  const why = body.error ?? `${r.status} ${r.statusText}`;
  if (r.status === 401) throw new Error(`${why} Open this page as ${location.origin}/#token=YOUR_TOKEN`);
  if (!r.ok) throw Object.assign(new Error(why), { status: r.status });
  return body;
});
const post = (path, body) => api(path, { method: 'POST', body: JSON.stringify(body ?? {}) });

const canvas = $('view');
const renderer = new Renderer(canvas);
const others = new OtherSets((sets) => renderer.setOthers(sets.drawable()));
// `?fps=N`: the frames per second the view keeps while it moves, lowering its resolution to do
// so (0: never lower it); js/resolution.js.
const motionFps = Number(new URLSearchParams(location.search).get('fps') ?? NaN);
if (motionFps >= 0) renderer.resolution.target = motionFps;
const camera = new OrbitCamera(canvas);
// `?budget=N`: the most particles a frame of a large scene carries (js/view.js).
const budget = Number(new URLSearchParams(location.search).get('budget')) > 0
  ? Math.round(Number(new URLSearchParams(location.search).get('budget'))) : BUDGET;
const viewSync = new ViewSync((op) => send(op));
const worker = new Worker(new URL('./codec/worker.js', import.meta.url), { type: 'module' });
const plots = new PlotPanel($('plots'));

const state = {
  scene: null, socket: null, wantOpen: false, running: false, requestedRtf: null,
  frames: 0, bytes: 0, lastBytes: 0, decodeMs: 0, renderFps: 0, lastStatus: null, bounds: null, spacing: 0,
  // The latest decoded frame not drawn yet: only it is drawn when frames come faster than the
  // page draws (uploading each would stall on the frame being drawn).
  nextFrame: null,
  // A frame waiting for the decoder, and frames skipped so (see decode()).
  decoding: false, heldBytes: null, skipped: 0,
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

/**
 * Fills the "Colour by" menu from a channel list. A scene opened afresh starts on none, which
 * draws each material in its own look (looks.js): a choice made for another scene's channels
 * says little of this one's. The scene shown, opened again (`keep`), keeps the choice if it is
 * still there.
 */
function showColourModes(channels, keep) {
  const sel = $('colour'), was = sel.value;
  sel.replaceChildren(...colourModes(channels).map((m) => new Option(m.label, m.value)));
  sel.value = keep && [...sel.options].some((o) => o.value === was) ? was : NONE;
  $('legend').hidden = sel.value === NONE;
}

/**
 * Fills the "Particles" menu: all of them, or one part (the scene's sets that are parts of its
 * particles: a solid's, the fluid's, by material); hidden where the scene has no parts. The
 * scene shown, opened again (`keep`), keeps the choice if it is still there.
 */
function showParts(scene, keep) {
  const sel = $('part'), was = sel.value;
  const parts = (scene.sets ?? []).filter((s) => s.part_of === 'particles');
  sel.replaceChildren(new Option('all', 'particles'), ...parts.map((s) => new Option(s.name, s.name)));
  sel.value = keep && [...sel.options].some((o) => o.value === was) ? was : 'particles';
  $('part-section').hidden = parts.length === 0;
}

/**
 * Offers a scene the server sized for this machine at its full size (sizing.js); hidden for any
 * other scene, or none.
 */
function showSizing(scene) {
  const full = fullSizeRequest(scene);
  $('sizing').hidden = !full;
  if (full) $('full-size').textContent = fullSizeLabel(scene.sizing);
}

/**
 * Re-reads the scene list and opens `select`, else the scene shown now if it is
 * still there, else the first. `reopen` opens it afresh even if it is the one
 * shown (after a reconnect the server may have restarted under the page).
 */
async function refreshScenes(select, reopen = false) {
  const scenes = await api('/scenes');
  routes.learn(scenes);
  if (replay.active) return;
  // A scene the list does not name (yet: in a cluster a worker lists another's new scene
  // after its next tick) is asked for by id, which reaches its worker (whose name the
  // answer carries, for the stream); one that does not exist or is not the user's is said
  // so, and the list's first opens instead.
  if (select != null && !scenes.some((s) => s.scene_id === select)) {
    const asked = await askFor(select).catch((e) => {
      showError('view-error', `scene ${select}: ${e.message}`);
      return null;
    });
    if (asked) {
      routes.learn([asked]);
      scenes.push(asked);
    }
  }
  const sel = $('scenes');
  sel.replaceChildren(...scenes.map((s) => new Option(`${s.scene_id}: ${s.name} (${s.particles} particles)`, s.scene_id)));
  const known = (i) => scenes.some((s) => s.scene_id === i);
  const id = [select, state.scene?.scene_id].find(known) ?? scenes[0]?.scene_id;
  if (id != null) {
    sel.value = id;
    if (reopen || id !== state.scene?.scene_id) {
      const listed = scenes.find((s) => s.scene_id === Number(id));
      // Another worker's scene is listed by name only: its worker gives the rest.
      open(listed.channels ? listed : await api(`/scenes/${listed.scene_id}`));
    }
  } else {
    close();
    state.scene = null;
    showSizing(null);
  }
}

/**
 * Scene `id`'s answer. In a cluster a worker that has not yet heard of a scene another worker
 * has just created answers 503 ("not known to this worker yet; retry"): its next tick (about a
 * second) tells where the scene is, so the page asks again, for up to 5 s.
 */
async function askFor(id) {
  for (let attempt = 1; ; attempt += 1) {
    try {
      return await api(`/scenes/${id}`);
    } catch (e) {
      if (e.status !== 503 || attempt >= 10) throw e;
      await new Promise((done) => setTimeout(done, 500));
    }
  }
}

function close() {
  state.wantOpen = false;
  state.socket?.close();
  state.socket = null;
  state.heldBytes = null;
  others.close();
  renderer.setOthers([]);
}

function open(scene) {
  const other = scene.scene_id !== state.scene?.scene_id;
  const changed = other || state.bounds === null;
  close();
  state.scene = scene;
  state.wantOpen = true;
  banner(scene.halt_reason ? `Halted: ${scene.halt_reason}` : null);
  showColourModes(scene.channels ?? DEFAULT_CHANNELS, !other);
  showParts(scene, !other);
  showSizing(scene);
  renderer.setLooks(sceneLooks(scene.materials).map((name) => LOOKS[name]));
  // Oriented particles (an elastic solid's `solid.oriented`) are drawn as ellipsoids.
  renderer.setOriented(orientedRadii(scene.scene, scene.particle_spacing));
  settings.show(scene);
  const tank = scene.scene?.boundaries?.find((b) => b.kind === 'box');
  showScene({ min: scene.bounds_min, max: scene.bounds_max }, wallLines(scene.scene), scene.particle_spacing, changed, tank);
  if (changed) showTerrain(scene);
  if (changed) {
    recorder.stop();
    plots.reset(`scene-${scene.scene_id}`);
    state.requestedRtf = null;
  }
  connect();
}

/** Draws the scene's terrains (fetched once per scene: walls never change), or none. */
function showTerrain(scene) {
  renderer.setTerrain([]);
  if (!scene.scene?.boundaries?.some((b) => b.kind === 'terrain')) return;
  api(`/scenes/${scene.scene_id}/terrain`)
    .then((t) => { if (state.scene?.scene_id === scene.scene_id) renderer.setTerrain(t.terrains); })
    .catch((e) => showError('view-error', `terrain: ${e.message}`));
}

/**
 * Sizes particles, sets the walls and the floor (under the `floor` box, else the bounds; null:
 * none), and frames the camera on `bounds` if `frame`.
 */
function showScene(bounds, walls, spacing, frame, floor = bounds) {
  state.bounds = bounds;
  renderer.setScene(walls, floor?.min, floor?.max, spacing);
  if (frame) frameCamera();
}

/** The part of the canvas not under the panels (CSS pixels): left and right edges. */
function freeRegion() {
  const w = canvas.clientWidth;
  let left = 0, right = w;
  // On a narrow screen the panels cover the view only while open; frame for the whole width.
  if (w >= 700) {
    if (!$('panel').classList.contains('collapsed')) left = $('panel').getBoundingClientRect().right;
    if (plots.visible) right = $('hud').getBoundingClientRect().left;
  }
  return right - left > w / 3 ? { left, right } : { left: 0, right: w };
}

/** Points the camera at the scene's bounds, framed in the part of the view the panels leave. */
function frameCamera() {
  if (!state.bounds) return;
  const { left, right } = freeRegion();
  camera.fit(state.bounds.min, state.bounds.max, (right - left) / Math.max(canvas.clientHeight, 1));
  state.framedFor = [left, right, Math.max(canvas.clientHeight, 1)].join();
}

function connect() {
  if (!state.wantOpen || !state.scene) return;
  const channel = $('colour').value;
  const url = new URL(routes.url(`/scenes/${state.scene.scene_id}/ws`), location.href);
  url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
  // The colour channel, oriented particles' orientations where the scene streams them, and
  // without a colour map each particle's material where materials differ in look (with a
  // melting scene's liquid fractions).
  const channels = [...streamedChannels(channel, state.scene.channels),
    ...lookChannels(channel, state.scene.channels, state.scene.materials)];
  // All the particles, or the part chosen (the solid's, the fluid's).
  const part = $('part').value || 'particles';
  // A scene larger than the budget: the part the camera sees (js/view.js).
  const aspect = canvas.clientWidth / Math.max(canvas.clientHeight, 1);
  const view = viewSync.start(state.scene.particles, budget, camera, aspect);
  url.search = new URLSearchParams({
    channels: channels.join(','), max_fps: '60', ...(part === 'particles' ? {} : { set: part }),
    ...(view ? { view: JSON.stringify(view) } : {}),
  });
  const ws = new WebSocket(url, credentials.protocols());
  ws.binaryType = 'arraybuffer';
  state.socket = ws;
  others.open(state.scene, (set, channels) => {
    const u = new URL(url);
    u.search = new URLSearchParams({ set, channels, max_fps: String(OTHER_FPS) });
    return u;
  }, credentials.protocols());
  ws.onmessage = (e) => {
    if (typeof e.data === 'string') return onText(JSON.parse(e.data));
    state.bytes += e.data.byteLength;
    state.lastBytes = e.data.byteLength;
    recorder.push(e.data);
    decode(e.data);
  };
  ws.onclose = () => {
    if (state.socket !== ws || !state.wantOpen) return;
    // The server went away or restarted: find it again, then the scene.
    setTimeout(reconnect, 1000);
  };
}

/** Re-reads the scene list every second until the server answers, then reopens the scene. */
function reconnect() {
  if (replay.active) return;
  refreshScenes(undefined, true).catch(() => setTimeout(reconnect, 1000));
}

/** A status of the scene shown: settings, halt banner, plots. */
function onStatus(scene) {
  settings.update(scene.scene);
  state.lastStatus = scene;
  // A halt banner goes once the scene is no longer halted (after a reset).
  if (scene.state !== 'halted' && $('banner').textContent.startsWith('Halted')) banner(null);
  state.running = scene.state === 'running';
  if (scene.state === 'halted') banner(`Halted: ${scene.halt_reason}`);
  plots.add(scene, performance.now() / 1000);
}

function onText(msg) {
  if (msg.type === 'status') onStatus(msg.scene);
  else if (msg.type === 'event' && msg.event === 'halted') {
    state.running = false;
    banner(`Halted: ${msg.reason}`);
  } else if (msg.type === 'event' && msg.event === 'parameter_changed') {
    send({ op: 'status' });
    $('param').value = '';
    $('param').placeholder = `applied: ${msg.overrides.join(' ')}`;
  } else if (msg.type === 'event' && msg.event === 'step_abandoned') {
    // A step call's caller left; the scene stopped there: show where.
    send({ op: 'status' });
  } else if (msg.type === 'event' && msg.event === 'deleted') {
    // Deleted by someone, or the server is shutting down: find what is there now.
    reconnect();
  } else if (msg.type === 'error') {
    banner(msg.message);
    setTimeout(() => banner(state.lastStatus?.halt_reason ? `Halted: ${state.lastStatus.halt_reason}` : null), 4000);
  }
}

/** Draws a decoded frame (live or replayed), coloured by the chosen channel. */
function showFrame(frame) {
  const values = colourValues(frame, $('colour').value, state.scene?.channels);
  if (values) {
    const [lo, hi] = valueRange(values);
    renderer.range = [lo, hi];
    $('legend-min').textContent = lo.toPrecision(3);
    $('legend-max').textContent = hi.toPrecision(3);
  }
  const orientations = renderer.radii ? orientationValues(frame, state.scene?.channels) : null;
  // Without a colour map, each particle in its material's look where the frame says which.
  const looks = values ? null : lookValues(frame, state.scene?.materials, state.scene?.channels);
  renderer.upload(frame.positions, values ?? looks, orientations, looks !== null);
}

/**
 * Sends a frame to the decoder, or holds it while the decoder is busy, in place of a frame held
 * before (skipped: the page asks for unordered frames, each whole on its own). A page that
 * draws or decodes slower than frames come thus shows the latest frame, never a backlog.
 */
function decode(bytes) {
  if (state.decoding) {
    if (state.heldBytes) state.skipped += 1;
    state.heldBytes = bytes;
    return;
  }
  state.decoding = true;
  worker.postMessage({ bytes }, [bytes]);
}

worker.onmessage = ({ data }) => {
  state.decoding = false;
  const held = state.heldBytes;
  state.heldBytes = null;
  if (held) decode(held);
  if (data.error) return banner(`Frame could not be decoded: ${data.error.message}`);
  if (replay.active) return;
  state.frames += 1;
  state.decodeMs = data.decodeMs ?? 0;
  state.nextFrame = data;
};

function send(op) {
  if (state.socket?.readyState === WebSocket.OPEN) state.socket.send(JSON.stringify(op));
}

/** A control of the scene shown, over REST; its error goes beside the scene controls. */
function control(path, body) {
  const scene = state.scene;
  return acting('controls-error', async () => {
    if (!scene) throw new Error('no scene: create one first');
    onStatus(await post(`/scenes/${scene.scene_id}/${path}`, body));
  });
}

function play() {
  state.requestedRtf = rtf();
  return control('run', { real_time_factor: state.requestedRtf });
}
function pause() { return control('pause'); }
function step() { return control('step', { steps: 1 }); }
function reset() { banner(null); return control('reset'); }
/** Changes tunable settings; the error goes beside the control used (`errorId`). */
function setParameters(overrides, errorId) {
  const scene = state.scene;
  return acting(errorId, async () => {
    if (!scene) throw new Error('no scene: create one first');
    onStatus(await post(`/scenes/${scene.scene_id}/parameters`, { overrides }));
  });
}

$('play').onclick = play;
$('pause').onclick = pause;
$('step').onclick = step;
$('reset').onclick = reset;
// Sliders for tunable settings: applied when released.
const settings = new SettingsPanel((overrides) => setParameters(overrides, 'settings-error'));

$('rtf').oninput = () => {
  const v = rtf();
  if (state.running) { state.requestedRtf = v; control('run', { real_time_factor: v }); }
};
$('colour').onchange = () => {
  $('legend').hidden = $('colour').value === NONE;
  if (replay.active) replay.redraw();
  else if (state.scene) open(state.scene);
};
$('part').onchange = () => { if (!replay.active && state.scene) open(state.scene); };
$('scenes').onchange = () => refreshScenes(Number($('scenes').value));
$('apply').onclick = () => {
  const text = $('param').value.trim();
  if (text) setParameters(text.split(/\s+/), 'param-error');
};
$('delete').onclick = () => acting('controls-error', async () => {
  if (!state.scene) throw new Error('no scene to delete');
  const id = state.scene.scene_id;
  close();
  state.scene = null;
  showSizing(null);
  try {
    await api(`/scenes/${id}`, { method: 'DELETE' });
  } finally {
    refreshScenes();
  }
});
async function create(body, errorId) {
  await acting(errorId, async () => {
    const scene = await post('/scenes', body);
    if (replay.active) replay.close();
    await refreshScenes(scene.scene_id);
  });
}
$('create').onclick = () => create({ preset: $('preset').value }, 'create-error');
$('full-size').onclick = () => create(fullSizeRequest(state.scene), 'create-error');
$('create-doc').onclick = () => {
  const text = $('document').value;
  create({ document: text, document_format: text.trim().startsWith('{') ? 'json' : 'toml' }, 'create-doc-error');
};
$('file').onchange = async () => { $('document').value = await $('file').files[0].text(); };

// View: the fluid's surface or spheres.
function setView(view) {
  const why = view === 'surface' ? renderer.surfaceUnsupported() : null;
  showError('view-error', why);
  renderer.view = why ? 'spheres' : view;
  $('view-mode').value = renderer.view;
  $('colour-section').classList.toggle('inactive', renderer.view === 'surface');
}
$('view-mode').onchange = () => setView($('view-mode').value);
$('other-sets').onchange = () => renderer.showOthers($('other-sets').checked);

// Recording and replay.
const recorder = new Recorder({
  button: $('record'), status: $('record-status'), errorId: 'record-error',
  onReplay: async (blob, name) => replay.open(await blob.arrayBuffer(), name),
});
$('record').onclick = () => {
  if (recorder.active) recorder.stop();
  else if (!state.scene || replay.active) showError('record-error', 'open a live scene to record it');
  else recorder.start(`${state.scene.name}-${state.scene.scene_id}`);
};
const replay = new Replay({
  errorId: 'replay-error',
  onOpen: (info, name) => {
    recorder.stop();
    close();
    state.lastStatus = null;
    plots.reset(name);
    banner(null);
    // The walls are not recorded; the positions' range (a cube around the domain) frames the
    // first view, until every frame is read and their extent is known.
    state.spacing = info.spacing;
    // A recording does not say how its particles are shaped: spheres.
    renderer.setOriented(null);
    showScene(info.bounds, new Float32Array(0), info.spacing, true, null);
  },
  onReady: (extent) => showScene(extent, new Float32Array(0), state.spacing, !camera.moved),
  onFrame: (message) => { state.decodeMs = message.decodeMs; state.nextFrame = message.frame; },
  onClose: () => { state.bounds = null; refreshScenes(undefined, true).catch((e) => banner(`Cannot reach the server: ${e.message}`)); },
});
$('recording-file').onchange = async () => {
  const file = $('recording-file').files[0];
  if (file) replay.open(await file.arrayBuffer(), file.name);
  $('recording-file').value = '';
};

// Panels, help and keys.
function togglePanel() {
  const collapsed = $('panel').classList.toggle('collapsed');
  $('panel-toggle').setAttribute('aria-expanded', String(!collapsed));
}
$('panel-toggle').onclick = togglePanel;
if (matchMedia('(max-width: 600px)').matches) togglePanel();
function toggleHelp(show = $('help').hidden) { $('help').hidden = !show; }
$('help-open').onclick = () => toggleHelp(true);
$('help-close').onclick = () => toggleHelp(false);
$('plots-open').onclick = () => plots.toggle();
fillHelp($('help'));
bindKeys({
  playPause: () => (replay.active ? replay.togglePlay() : state.running ? pause() : play()),
  step: () => (replay.active ? replay.step(1) : step()),
  reset: () => { if (!replay.active) reset(); },
  previous: () => replay.step(-1),
  next: () => replay.step(1),
  slower: () => replay.changeSpeed(-1),
  faster: () => replay.changeSpeed(1),
  view: () => setView(renderer.view === 'surface' ? 'spheres' : 'surface'),
  frame: frameCamera,
  plots: () => plots.toggle(),
  help: () => toggleHelp(),
  dismiss: () => toggleHelp(false),
});

// Colour-map legend, drawn once.
{
  const g = $('legend-bar').getContext('2d'), grad = g.createLinearGradient(0, 0, 200, 0);
  grad.addColorStop(0, 'rgb(68,1,84)'); grad.addColorStop(0.5, 'rgb(33,145,140)'); grad.addColorStop(1, 'rgb(253,231,37)');
  g.fillStyle = grad;
  g.fillRect(0, 0, 200, 10);
}

// Render loop and stats overlay.
let fpsFrames = 0, fpsStart = performance.now(), lastPoll = 0;
function frame(now) {
  replay.tick(now);
  if (state.nextFrame) {
    showFrame(state.nextFrame);
    state.nextFrame = null;
  }
  const w = canvas.clientWidth, h = Math.max(canvas.clientHeight, 1);
  const { left, right } = freeRegion();
  // Panels opened or closed, or the window resized: frame again unless the user moved the camera.
  if (!camera.moved && state.framedFor !== [left, right, h].join()) frameCamera();
  const shift = (left + right) / w - 1;
  if (!replay.active) viewSync.update(camera, w / h, now);
  if (renderer.draw(camera.projection(w / h, shift), camera.view(), camera.distance, now)) fpsFrames += 1;
  // The scene's status twice a second, for the plots and the overlay.
  if (now - lastPoll > 500) {
    lastPoll = now;
    send({ op: 'status' });
  }
  if (now - fpsStart > 1000) {
    state.renderFps = (fpsFrames * 1000) / (now - fpsStart);
    fpsFrames = 0;
    fpsStart = now;
    const s = replay.active ? null : state.lastStatus;
    const rt = realTime(s, plots.series.recentRealTime(3), state.requestedRtf);
    $('rtf-achieved').textContent = rt.text ? `achieved ${rt.text}` : '';
    $('rtf-achieved').classList.toggle('slow', rt.slow);
    $('stats').textContent = statsText({
      renderer, status: s, replay: replay.active ? replay.describe() : null, realTime: rt, stream: state,
      others: others.summary(), sizing: replay.active ? null : state.scene?.sizing,
      inView: replay.active || viewSync.budget === null ? null : state.scene?.particles,
    });
  }
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

rtf();
setView('surface');
api('/presets').then((p) => $('preset').replaceChildren(...p.map((n) => new Option(n, n)))).catch((e) => showError('create-error', e.message));
refreshScenes(askedScene).catch((e) => banner(`Cannot reach the server: ${e.message}`));
