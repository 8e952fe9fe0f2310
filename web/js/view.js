/**
 * The region of a large scene the page streams. A scene of more particles than the page's
 * budget is streamed through a view (server/src/service/view.rs): the camera's cone, at most
 * `budget` particles, every particle near the camera and fewer farther out, the same ones from
 * frame to frame. As the camera moves the page sends the new view on its socket
 * (`{"op": "view", ...}`), at most every {@link EVERY_MS} ms and only when it moved enough to
 * change what is seen; the server then sends the scene's state again as the new view shows it,
 * also while the scene is paused. A scene within the budget streams whole, as always.
 * @module
 */

import { FOVY, orbitDirection } from './camera.js';

/** Most particles a frame carries by default: what software GL draws at a few frames a second. */
export const BUDGET = 400_000;
/** Least time between two view messages (ms). */
export const EVERY_MS = 200;

/**
 * The view of an orbit camera (`target`, `distance`, `yaw`, `pitch`) on a canvas `aspect` wide
 * over high: its eye, its direction, the cone holding the whole screen (its half angle the
 * screen diagonal's), and the budget.
 * @param {{target: number[], distance: number, yaw: number, pitch: number}} camera
 * @param {number} aspect @param {number} budget
 * @returns {{camera: {position: number[], direction: number[], fov_deg: number}, budget: number}}
 */
export function cameraView(camera, aspect, budget) {
  const back = orbitDirection(camera.yaw, camera.pitch);
  const position = camera.target.map((t, k) => t + camera.distance * back[k]);
  const half = Math.atan(Math.tan(FOVY / 2) * Math.hypot(1, aspect));
  return { camera: { position, direction: back.map((c) => -c), fov_deg: (360 * half) / Math.PI }, budget };
}

/**
 * Whether view `b` differs from `a` enough to ask for it: the eye moved by more than 1 % of
 * `distance` (the camera's from its target), the direction turned by more than half a degree,
 * the cone widened or narrowed by more than a degree, or the budget changed.
 */
export function changed(a, b, distance) {
  if (!a || a.budget !== b.budget) return true;
  const moved = Math.hypot(...a.camera.position.map((p, k) => p - b.camera.position[k]));
  const cos = a.camera.direction.reduce((s, d, k) => s + d * b.camera.direction[k], 0);
  return moved > 0.01 * distance || cos < Math.cos((0.5 * Math.PI) / 180) || Math.abs(a.camera.fov_deg - b.camera.fov_deg) > 1;
}

/** Keeps a socket's view on the camera. */
export class ViewSync {
  /** @param {(op: object) => void} send sends a control message on the scene's socket */
  constructor(send) {
    this.send = send;
    /** The budget, or null where the scene streams whole. */
    this.budget = null;
    this.last = null;
    this.lastAt = -Infinity;
  }

  /**
   * Starts on a scene of `particles` particles: a view if they are more than `budget`. Returns
   * the first view (for the socket's query), or null.
   */
  start(particles, budget, camera, aspect) {
    this.budget = particles > budget ? budget : null;
    this.last = this.budget === null ? null : cameraView(camera, aspect, this.budget);
    this.lastAt = -Infinity;
    return this.last;
  }

  /** Sends the camera's view if it changed enough and the last went long enough ago (`now` in ms). */
  update(camera, aspect, now) {
    if (this.budget === null || now - this.lastAt < EVERY_MS) return;
    const view = cameraView(camera, aspect, this.budget);
    if (!changed(this.last, view, camera.distance)) return;
    this.send({ op: 'view', ...view });
    this.last = view;
    this.lastAt = now;
  }
}
