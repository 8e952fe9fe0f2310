/**
 * The canvas's resolution while the picture moves. On software GL (a machine without a GPU) a
 * frame's cost grows with the pixels drawn, and a view that turns at 3 frames a second is hard
 * to steer. While frames follow each other (the camera turning, a scene playing fast) the
 * renderer draws at a fraction of the canvas's resolution, lowered while the frame rate stays
 * under `target` and raised again while it is well over; once the picture has stood still for
 * `idleMs` it is drawn once more at full resolution, so a still picture is always sharp. Where
 * frames come fast at full resolution (a GPU) nothing changes.
 * @module
 */

/** Step by which the resolution falls or rises, per measurement. */
const STEP = 0.85;
/** Frames a measurement takes, at least, and its span in ms, at least. */
const WINDOW_FRAMES = 4;
const WINDOW_MS = 1000;
/** Longer than this (ms) between frames is a pause (a hidden tab), not a frame's cost. */
const MAX_FRAME_MS = 1000;

/** Picks the resolution of each frame. */
export class Resolution {
  /**
   * @param {{target?: number, min?: number, idleMs?: number}} [o] frames per second to keep
   *   while moving, the lowest fraction of the canvas's resolution (per axis), and the still
   *   time (ms) after which the picture is drawn sharp
   */
  constructor({ target = 8, min = 0.5, idleMs = 500 } = {}) {
    this.target = target;
    this.min = min;
    this.idleMs = idleMs;
    /** Fraction of the canvas's resolution (per axis) that moving frames are drawn at. */
    this.moving = 1;
    this.sharp = true;
    /** When the last moving frame was drawn, and the animation frames since that drew none. */
    this.lastMoving = -Infinity;
    this.skipped = Infinity;
    this.frames = 0;
    this.time = 0;
  }

  /**
   * Called once per animation frame at time `now` (ms): whether the picture changed since the
   * last frame drawn. Returns the fraction of the resolution to draw at, or null for no drawing.
   * @param {number} now
   * @param {boolean} changed
   * @returns {number|null}
   */
  next(now, changed) {
    let scale = null;
    if (changed) {
      // A moving frame drawn one or two animation frames after the last: the time between them
      // is what a frame costs (the browser comes round once it has drawn). Frames further apart
      // came as the picture changed, not as fast as they could be drawn.
      if (this.skipped <= 1 && now - this.lastMoving < MAX_FRAME_MS) this.#measure(now - this.lastMoving);
      scale = this.moving;
      this.sharp = scale === 1;
      this.lastMoving = now;
      this.skipped = 0;
    } else {
      this.skipped += 1;
      if (!this.sharp && now - this.lastMoving >= this.idleMs) {
        // The sharp frame after a pause is not a moving frame: its cost is not measured.
        scale = 1;
        this.sharp = true;
        this.skipped = Infinity;
      }
    }
    return scale;
  }

  #measure(ms) {
    this.frames += 1;
    this.time += ms;
    if (this.frames < WINDOW_FRAMES || this.time < WINDOW_MS) return;
    const fps = (1000 * this.frames) / this.time;
    if (fps < 0.8 * this.target) this.moving = Math.max(this.min, this.moving * STEP);
    else if (fps > 1.5 * this.target) this.moving = this.moving / STEP > 0.97 ? 1 : this.moving / STEP;
    this.frames = 0;
    this.time = 0;
  }
}
