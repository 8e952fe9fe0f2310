// Orbit camera: drag to rotate about the scene centre, wheel to zoom.
// Matrices are column-major Float32Array(16), as WebGL expects.

/** Perspective projection (fovy in radians). */
export function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
  return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0]);
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

/** An orbit camera bound to a canvas's mouse events. */
export class OrbitCamera {
  constructor(canvas) {
    this.target = [0, 0, 0];
    this.distance = 3;
    this.yaw = 0.6;
    this.pitch = 0.35;
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      this.yaw -= (e.clientX - drag[0]) * 0.005;
      this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + (e.clientY - drag[1]) * 0.005));
      drag = [e.clientX, e.clientY];
    });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.distance *= Math.exp(e.deltaY * 0.001);
    }, { passive: false });
  }

  /** Frames the box [min, max]. */
  fit(min, max) {
    this.target = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
    this.distance = 1.1 * Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  }

  /** The view matrix. */
  view() {
    const c = Math.cos(this.pitch);
    const eye = [
      this.target[0] + this.distance * c * Math.sin(this.yaw),
      this.target[1] + this.distance * Math.sin(this.pitch),
      this.target[2] + this.distance * c * Math.cos(this.yaw),
    ];
    return lookAt(eye, this.target);
  }
}
