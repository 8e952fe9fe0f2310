// Orbit camera: drag to rotate about the scene centre, wheel or pinch to zoom, right-drag or
// shift-drag to pan. Matrices are column-major Float32Array(16), as WebGL expects.

/** Vertical field of view (radians). */
export const FOVY = 0.8;

/**
 * Perspective projection (fovy in radians), its centre moved `shift` (in normalised device x)
 * so a scene framed in part of the canvas, beside a panel, is centred there.
 */
export function perspective(fovy, aspect, near, far, shift = 0) {
  const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
  return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, -shift, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0]);
}

/** View matrix looking from `eye` at `target` with +y up. */
export function lookAt(eye, target) {
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const norm = (v) => { const l = Math.hypot(...v) || 1; return v.map((c) => c / l); };
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const z = norm(sub(eye, target)), x = norm(cross([0, 1, 0], z)), y = cross(z, x);
  return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
    -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
}

/** The eye's direction from the target (unit) at `yaw` and `pitch` (radians). */
export function orbitDirection(yaw, pitch) {
  const c = Math.cos(pitch);
  return [c * Math.sin(yaw), Math.sin(pitch), c * Math.cos(yaw)];
}

/**
 * The least distance from the box's centre, looking at it from `yaw` and `pitch`, at which all
 * eight corners of the box [min, max] lie in the view (vertical field `fovy`, width over height
 * `aspect`), with `margin` (1.08: 8 % to spare at the tightest side).
 */
export function framingDistance(min, max, yaw, pitch, fovy, aspect, margin = 1.08) {
  const z = orbitDirection(yaw, pitch);
  const x = [z[2], 0, -z[0]].map((v) => v / Math.hypot(z[2], z[0]));
  const y = [z[1] * x[2], z[2] * x[0] - z[0] * x[2], -z[1] * x[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const tanV = Math.tan(fovy / 2), tanH = tanV * aspect;
  let d = 0;
  for (let i = 0; i < 8; i++) {
    const rel = [0, 1, 2].map((k) => ((i >> k) & 1 ? max[k] - min[k] : min[k] - max[k]) / 2);
    // A corner at depth d - zc in front of the eye shows if |xc| <= tanH (d - zc), likewise y.
    const zc = dot(rel, z);
    d = Math.max(d, zc + (margin * Math.abs(dot(rel, x))) / tanH, zc + (margin * Math.abs(dot(rel, y))) / tanV);
  }
  return d;
}

/** An orbit camera bound to a canvas's pointer events. */
export class OrbitCamera {
  constructor(canvas) {
    this.target = [0, 0, 0];
    this.distance = 3;
    this.yaw = 0.5;
    this.pitch = 0.4;
    /** Whether the user moved the camera since it was last fitted. */
    this.moved = false;
    const pointers = new Map();
    let pinch = 0;
    canvas.addEventListener('pointerdown', (e) => {
      pointers.set(e.pointerId, [e.clientX, e.clientY]);
      canvas.setPointerCapture(e.pointerId);
      if (pointers.size === 2) pinch = spread(pointers);
    });
    const up = (e) => { pointers.delete(e.pointerId); };
    canvas.addEventListener('pointerup', up);
    canvas.addEventListener('pointercancel', up);
    canvas.addEventListener('pointermove', (e) => {
      const last = pointers.get(e.pointerId);
      if (!last) return;
      pointers.set(e.pointerId, [e.clientX, e.clientY]);
      this.moved = true;
      if (pointers.size === 2) {
        const now = spread(pointers);
        if (pinch > 0 && now > 0) this.distance *= pinch / now;
        pinch = now;
        return;
      }
      const dx = e.clientX - last[0], dy = e.clientY - last[1];
      if (e.shiftKey || e.buttons === 2) this.pan(dx, dy, canvas.clientHeight);
      else {
        this.yaw -= dx * 0.005;
        this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + dy * 0.005));
      }
    });
    canvas.addEventListener('contextmenu', (e) => e.preventDefault());
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.moved = true;
      this.distance *= Math.exp(e.deltaY * 0.001);
    }, { passive: false });
  }

  /**
   * Frames the box [min, max] (m): looks at its centre from the default direction, from as near
   * as shows all of it in a view `aspect` wide over high.
   */
  fit(min, max, aspect) {
    this.target = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
    this.yaw = 0.5;
    this.pitch = 0.4;
    this.distance = framingDistance(min, max, this.yaw, this.pitch, FOVY, aspect);
    this.moved = false;
    this.near = this.distance / 1000;
    this.far = this.distance * 10;
  }

  /** Moves the target by a drag of `dx`, `dy` pixels in a view `height` pixels high. */
  pan(dx, dy, height) {
    const scale = (2 * this.distance * Math.tan(FOVY / 2)) / Math.max(height, 1);
    const v = this.view();
    // Camera right and up are the view matrix's first two rows.
    for (let k = 0; k < 3; k++) this.target[k] += scale * (-dx * v[4 * k] + dy * v[4 * k + 1]);
  }

  /** Projection for a canvas `aspect` wide over high, centred `shift` off in device x. */
  projection(aspect, shift = 0) {
    return perspective(FOVY, aspect, this.near ?? 0.01, Math.max(this.far ?? 100, this.distance * 4), shift);
  }

  /** The eye's position. */
  eye() {
    return orbitDirection(this.yaw, this.pitch).map((v, k) => this.target[k] + this.distance * v);
  }

  /** The view matrix. */
  view() {
    return lookAt(this.eye(), this.target);
  }
}

/** Distance between the first two pointers. */
function spread(pointers) {
  const [a, b] = [...pointers.values()];
  return Math.hypot(a[0] - b[0], a[1] - b[1]);
}
