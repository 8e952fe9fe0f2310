// Replay of a recording (the page's, or one `floectl record` made) without any scene running: a
// timeline to scrub, play and pause, step frame by frame and set the speed. Frames are decoded
// in a Web Worker (replay-worker.js); while one is being decoded only the latest frame asked for
// waits, so scrubbing never queues up work.

import { showError } from './notify.js';
import { advance, naturalSpeed } from './player.js';

const $ = (id) => document.getElementById(id);

/** Playback speeds offered (simulated seconds per wall second). */
export const SPEEDS = Object.freeze([0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.25, 0.5, 1, 2, 4, 10]);

/** The timeline and the recording shown. */
export class Replay {
  /**
   * @param {{onOpen: (info: object, name: string) => void, onReady: (extent: object) => void,
   *   onFrame: (message: object) => void, onClose: () => void, errorId: string}} hooks `onOpen`
   *   gets the worker's `opened` reply; `onReady` the extent of every frame's particles
   *   (`{min, max}`, m) once all are indexed; `onFrame` a decoded frame (`{index, frame,
   *   decodeMs}`); `onClose` runs after the replay ends
   */
  constructor(hooks) {
    this.hooks = hooks;
    this.worker = null;
    this.info = null;
    this.name = '';
    /** The frame shown, and the one being decoded (null: none). */
    this.shown = -1;
    this.pending = null;
    this.wanted = null;
    /** Playback clock: the frame due and the simulated time since it became due. */
    this.clock = { index: 0, elapsed: 0 };
    this.playing = false;
    this.lastTick = null;
    $('tl-speed').replaceChildren(...SPEEDS.map((s) => new Option(`${s}×`, String(s))));
    $('tl-speed').value = '1';
    $('tl-play').onclick = () => this.togglePlay();
    $('tl-prev').onclick = () => this.step(-1);
    $('tl-next').onclick = () => this.step(1);
    $('tl-close').onclick = () => this.close();
    $('tl-slider').oninput = () => this.scrub(Number($('tl-slider').value));
  }

  /** Whether a recording is open. */
  get active() {
    return this.worker !== null;
  }

  /** The playback speed. */
  get speed() {
    return Number($('tl-speed').value);
  }

  /** Opens a recording's bytes; `name` is shown. */
  open(buffer, name) {
    this.worker?.terminate();
    this.worker = new Worker(new URL('./replay-worker.js', import.meta.url), { type: 'module' });
    this.worker.onmessage = ({ data }) => this.#onMessage(data);
    this.worker.onerror = (e) => this.#fail(`the replay's worker failed: ${e.message}`);
    this.info = null;
    this.name = name;
    this.shown = -1;
    this.pending = -1;
    this.wanted = null;
    this.playing = false;
    this.clock = { index: 0, elapsed: 0 };
    showError(this.hooks.errorId, null);
    $('timeline').hidden = false;
    $('tl-label').textContent = `opening ${name}`;
    this.worker.postMessage({ open: buffer }, [buffer]);
  }

  /** Ends the replay. */
  close() {
    if (!this.worker) return;
    this.worker.terminate();
    this.worker = null;
    this.info = null;
    $('timeline').hidden = true;
    this.hooks.onClose();
  }

  /** Shows frame `k` (the user moved the timeline), pausing playback's clock there. */
  scrub(k) {
    this.clock = { index: k, elapsed: 0 };
    this.#seek(k);
  }

  /** Decodes the frame shown again (to colour it afresh). */
  redraw() {
    if (this.shown < 0) return;
    const k = this.shown;
    this.shown = -1;
    this.#seek(k);
  }

  /** One frame forward (1) or back (-1), paused. */
  step(by) {
    if (!this.info) return;
    this.#setPlaying(false);
    this.scrub(Math.max(0, Math.min(this.info.frames - 1, this.clock.index + by)));
  }

  /** Plays or pauses; playing from the last frame starts over. */
  togglePlay() {
    if (!this.info) return;
    if (!this.playing && this.clock.index >= this.info.frames - 1) this.scrub(0);
    this.#setPlaying(!this.playing);
  }

  /** The next speed up (1) or down (-1). */
  changeSpeed(by) {
    const i = SPEEDS.indexOf(this.speed) + by;
    if (i >= 0 && i < SPEEDS.length) $('tl-speed').value = String(SPEEDS[i]);
  }

  /** Advances playback to the wall-clock time `now` (ms); call once per animation frame. */
  tick(now) {
    const dt = this.lastTick === null ? 0 : (now - this.lastTick) / 1000;
    this.lastTick = now;
    if (!this.playing || !this.info) return;
    this.clock = advance(this.info.times, this.clock.index, this.clock.elapsed + dt * this.speed);
    this.#seek(this.clock.index);
    if (this.clock.index >= this.info.frames - 1) this.#setPlaying(false);
  }

  /** Lines for the stats overlay. */
  describe() {
    if (!this.info) return [`replay     ${this.name} (opening)`];
    const i = Math.max(this.shown, 0);
    return [
      `replay     ${this.name}`,
      `frame      ${i + 1} / ${this.info.frames}`,
      `sim time   ${this.info.times[i].toFixed(3)} s`,
    ];
  }

  #setPlaying(on) {
    this.playing = on;
    $('tl-play').textContent = on ? 'Pause' : 'Play';
  }

  /** Asks for frame `k`; while a frame is being decoded, only the latest request waits. */
  #seek(k) {
    if (k === this.shown && this.pending === null) return;
    if (this.pending !== null) {
      this.wanted = k;
      return;
    }
    this.pending = k;
    this.wanted = null;
    this.worker.postMessage({ seek: k, id: k });
  }

  #onMessage(data) {
    if (data.opened) {
      this.info = data.opened;
      const slider = $('tl-slider');
      slider.max = String(this.info.frames - 1);
      slider.value = '0';
      $('tl-speed').value = String(naturalSpeed(this.info.times, SPEEDS));
      this.hooks.onOpen(this.info, this.name);
    } else if (data.progress !== undefined) {
      $('tl-progress').textContent = data.progress < 1 ? `indexing ${Math.round(data.progress * 100)} %` : '';
    } else if (data.ready) {
      $('tl-progress').textContent = '';
      $('tl-progress').dataset.indexMs = data.ready.indexMs.toFixed(0);
      this.hooks.onReady(data.ready.extent);
    } else if (data.error) {
      if (data.id === undefined) this.#fail(data.error);
      else {
        showError(this.hooks.errorId, data.error);
        this.#next();
      }
    } else if (data.frame) {
      this.shown = data.index;
      this.hooks.onFrame(data);
      $('tl-slider').value = String(data.index);
      $('tl-label').textContent = `frame ${data.index + 1} / ${this.info.frames}, t = ${this.info.times[data.index].toFixed(3)} s`;
      // The worker's time for this seek (measure_fps.mjs reads it).
      $('tl-label').dataset.seekMs = data.decodeMs.toFixed(1);
      this.#next();
    }
  }

  /** After a reply: the frame asked for meanwhile, if any. */
  #next() {
    this.pending = null;
    const k = this.wanted;
    if (k !== null && k !== this.shown) this.#seek(k);
  }

  /** A recording that cannot be replayed: say why beside the control that opened it. */
  #fail(message) {
    this.close();
    showError(this.hooks.errorId, message);
  }
}
