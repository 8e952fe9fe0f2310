// The floor under a scene: a faint checkerboard at the bottom of its bounds, so depth and scale
// read at a glance and the surface view has something to refract.

import { programWith } from './gl.js';

const VERT = `#version 300 es
uniform mat4 u_proj, u_view;
uniform vec3 u_min, u_max;
out vec2 v_xz;
void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
  v_xz = mix(u_min.xz, u_max.xz, corner);
  gl_Position = u_proj * u_view * vec4(v_xz.x, u_min.y, v_xz.y, 1.0);
}`;

const FRAG = `#version 300 es
precision highp float;
uniform float u_cell;
in vec2 v_xz;
out vec4 colour;
void main() {
  vec2 c = floor(v_xz / u_cell);
  float odd = mod(c.x + c.y, 2.0);
  colour = vec4(mix(vec3(0.16, 0.18, 0.2), vec3(0.24, 0.26, 0.28), odd), 1.0);
}`;

/**
 * A round cell size (1, 2 or 5 times a power of ten, m) giving about `cells` cells across `extent`.
 * @param {number} extent metres @param {number} [cells]
 */
export function cellSize(extent, cells = 10) {
  const raw = extent / cells;
  const p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw);
}

/** Draws the floor in a WebGL2 context. */
export class Floor {
  constructor(gl) {
    this.gl = gl;
    Object.assign(this, programWith(gl, VERT, FRAG, ['u_proj', 'u_view', 'u_min', 'u_max', 'u_cell']));
    this.vao = gl.createVertexArray();
    this.bounds = null;
  }

  /** The floor spans `min` to `max` (m) in x and z, at height `min[1]`; null: no floor. */
  set(min, max) {
    this.bounds = min && max ? { min, max, cell: cellSize(Math.max(max[0] - min[0], max[2] - min[2])) } : null;
  }

  /** Draws with the camera's matrices. */
  draw(proj, view) {
    if (!this.bounds) return;
    const gl = this.gl, { min, max, cell } = this.bounds;
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(this.u.u_proj, false, proj);
    gl.uniformMatrix4fv(this.u.u_view, false, view);
    gl.uniform3fv(this.u.u_min, min);
    gl.uniform3fv(this.u.u_max, max);
    gl.uniform1f(this.u.u_cell, cell);
    gl.bindVertexArray(this.vao);
    // Behind the walls' lines along its edges.
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4);
    gl.disable(gl.POLYGON_OFFSET_FILL);
  }
}
