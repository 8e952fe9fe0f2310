// Draws the scene's other sets (sets.js): a grid as one tile per cell, coloured by its value
// through the colour map (a flat grid, one cell high, at its floor or at its cells' surface
// heights where the set names a surface channel; a deeper one layer by layer at each cell's
// centre height), and a module's own particles as points in the solid look. A set in the snow
// look is drawn white: its points as flakes (six-armed sprites, each of its own size, spinning
// and tumbling, as the snow thesis's textured flakes), and its tiles blended from the ground's
// grey to white by value (more snow, whiter; none, bare ground).

import { programWith } from './gl.js';

/** A flake's size (m) as drawn: larger than a real one's, to be seen. */
const FLAKE_SIZE = 0.15;

const VERT = `#version 300 es
#define FLAKE_SIZE ${FLAKE_SIZE.toFixed(3)}
uniform mat4 u_proj, u_view;
uniform float u_point, u_sprite, u_time, u_viewport;
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_colour;
out vec3 v_colour;
out float v_angle;
void main() {
  v_colour = a_colour;
  // A flake's own size, spin and tumbling rate, from a hash of its index; its size on screen
  // falls with its distance D as the snow thesis's sprites do (viewport height x size /
  // sqrt(A + B D + C D^2), with A = B = 0, C = 1), within 2 to 32 pixels.
  float h = fract(sin(float(gl_VertexID) * 12.9898) * 43758.5453);
  vec4 eye = u_view * vec4(a_pos, 1.0);
  float flake = u_viewport * FLAKE_SIZE * (0.7 + 0.9 * h) / max(-eye.z, 1e-3);
  gl_PointSize = u_sprite > 0.5 ? clamp(flake, 2.0, 32.0) : u_point;
  v_angle = u_sprite > 0.5 ? h * 6.2832 + u_time * (0.5 + 2.0 * h) : 0.0;
  gl_Position = u_proj * eye;
}`;

const FRAG = `#version 300 es
precision highp float;
uniform float u_sprite;
in vec3 v_colour;
in float v_angle;
out vec4 colour;
void main() {
  if (u_sprite > 0.5) {
    // A six-armed flake turned by its spin, squashed as it tumbles (seen edge-on).
    vec2 p = gl_PointCoord * 2.0 - 1.0;
    float c = cos(v_angle), s = sin(v_angle);
    p = mat2(c, -s, s, c) * p;
    p.y /= max(0.25, abs(cos(0.7 * v_angle)));
    float arms = 0.3 + 0.7 * pow(abs(cos(3.0 * atan(p.y, p.x))), 6.0);
    if (length(p) > arms) discard;
  }
  colour = vec4(v_colour, 1.0);
}`;

/** The colour map of the particles' spheres (render.js), for `t` in 0 to 1. */
export function ramp(t) {
  const a = [0.267, 0.005, 0.329], b = [0.128, 0.567, 0.551], c = [0.993, 0.906, 0.144];
  const [p, q, s] = t < 0.5 ? [a, b, t * 2] : [b, c, t * 2 - 1];
  return p.map((x, k) => x + (q[k] - x) * s);
}

/** A tile's share of its cell (the rest is the gap between tiles). */
const TILE = 0.9;

/** The snow look's white, and the bare ground's grey a snow grid blends from. */
const SNOW = [0.95, 0.97, 1.0], BARE = [0.35, 0.33, 0.3];

/**
 * Triangles (positions and colours, three floats per vertex) of a grid's tiles: cell (i, j, k)
 * (x fastest) a square of `TILE` of its cell in x-z at height `heights[c]` where given, else
 * `origin.y` for a grid one cell high, else at its centre's; coloured by `values` over their
 * range through the colour map, or from bare grey to white in the snow look (the snow thesis's
 * blend of snow over ground by coverage: white by the share of the deepest snow, times `shades`).
 * @param {{origin: number[], size: number[], dims: number[]}} grid
 * @param {Float32Array|null} values one per cell
 * @param {Float32Array|null} [heights] one per cell (m)
 * @param {string} [look] the set's look ('snow', or '' for the colour map)
 * @param {Float32Array|null} [shades] one per cell, 0 to 1: how much of the look to draw
 */
export function gridTiles(grid, values, heights = null, look = '', shades = null) {
  const { origin, size, dims } = grid;
  const cell = [0, 1, 2].map((a) => size[a] / dims[a]);
  const n = dims[0] * dims[1] * dims[2];
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < n && values; i++) { lo = Math.min(lo, values[i]); hi = Math.max(hi, values[i]); }
  const positions = new Float32Array(n * 18), colours = new Float32Array(n * 18);
  const half = [0.5 * TILE * cell[0], 0.5 * TILE * cell[2]];
  for (let k = 0; k < dims[2]; k++) {
    for (let j = 0; j < dims[1]; j++) {
      for (let i = 0; i < dims[0]; i++) {
        const c = i + dims[0] * (j + dims[1] * k);
        const x = origin[0] + (i + 0.5) * cell[0], z = origin[2] + (k + 0.5) * cell[2];
        const y = heights ? heights[c] : dims[1] === 1 ? origin[1] : origin[1] + (j + 0.5) * cell[1];
        const corners = [[-1, -1], [1, -1], [1, 1], [-1, -1], [1, 1], [-1, 1]];
        const t = values && hi > lo ? (values[c] - lo) / (hi - lo) : 0.5;
        const depth = values && hi > 0 ? Math.min(1, Math.max(0, values[c]) / hi) : 0;
        const white = depth * (shades ? Math.min(1, Math.max(0, shades[c])) : 1);
        const rgb = look === 'snow' ? BARE.map((b, k) => b + (SNOW[k] - b) * white) : ramp(t);
        corners.forEach(([sx, sz], v) => {
          positions.set([x + sx * half[0], y, z + sz * half[1]], c * 18 + v * 3);
          colours.set(rgb, c * 18 + v * 3);
        });
      }
    }
  }
  return { positions, colours, count: n * 6 };
}

/** The renderer of the other sets. */
export class Others {
  constructor(gl) {
    this.gl = gl;
    this.program = programWith(gl, VERT, FRAG, ['u_proj', 'u_view', 'u_point', 'u_sprite', 'u_time', 'u_viewport']);
    /** @type {{mode: number, count: number, sprite: boolean, vao: WebGLVertexArrayObject, buffers: WebGLBuffer[]}[]} */
    this.meshes = [];
    /** Whether they are drawn. */
    this.visible = true;
  }

  /** Takes what to draw (`OtherSets.drawable()`); `solid` is the RGB of a set's particles. */
  set(sets, solid) {
    const gl = this.gl;
    for (const m of this.meshes) {
      gl.deleteVertexArray(m.vao);
      m.buffers.forEach((b) => gl.deleteBuffer(b));
    }
    this.meshes = sets.map((s) => {
      const rgb = s.look === 'snow' ? SNOW : solid;
      const mesh = s.grid
        ? { mode: gl.TRIANGLES, ...gridTiles(s.grid, s.values, s.heights, s.look, s.shades) }
        : { mode: gl.POINTS, positions: s.positions, colours: new Float32Array(s.positions.length).map((_, i) => rgb[i % 3]),
          count: s.positions.length / 3 };
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const buffers = [mesh.positions, mesh.colours].map((data, location) => {
        const b = gl.createBuffer();
        gl.bindBuffer(gl.ARRAY_BUFFER, b);
        gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
        gl.enableVertexAttribArray(location);
        gl.vertexAttribPointer(location, 3, gl.FLOAT, false, 0, 0);
        return b;
      });
      gl.bindVertexArray(null);
      return { mode: mesh.mode, count: mesh.count, sprite: !s.grid && s.look === 'snow', vao, buffers };
    });
  }

  /** Draws them with the camera's matrices (depth-tested, with the particles). */
  draw(proj, view) {
    if (!this.visible || this.meshes.length === 0) return;
    const gl = this.gl, { program, u } = this.program;
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(program);
    gl.uniformMatrix4fv(u.u_proj, false, proj);
    gl.uniformMatrix4fv(u.u_view, false, view);
    gl.uniform1f(u.u_point, 6.0 * devicePixelRatio);
    gl.uniform1f(u.u_time, performance.now() / 1000);
    gl.uniform1f(u.u_viewport, gl.drawingBufferHeight);
    for (const m of this.meshes) {
      gl.uniform1f(u.u_sprite, m.sprite ? 1 : 0);
      gl.bindVertexArray(m.vao);
      gl.drawArrays(m.mode, 0, m.count);
    }
    gl.bindVertexArray(null);
  }
}
