// Wireframes of a scene's box walls, drawn behind the particles, so a viewer sees the tank the
// fluid moves in. Plane walls are not drawn: their extent depends on tangents the engine picks.

import { program } from './gl.js';

const VERT = `#version 300 es
uniform mat4 u_proj, u_view;
in vec3 a_pos;
void main() { gl_Position = u_proj * u_view * vec4(a_pos, 1.0); }`;

const FRAG = `#version 300 es
precision mediump float;
out vec4 colour;
void main() { colour = vec4(0.45, 0.47, 0.5, 1.0); }`;

/**
 * The 12 edges of the box from `min` to `max` (m), as 24 line endpoints (x, y, z each).
 * @param {number[]} min @param {number[]} max
 * @returns {Float32Array}
 */
export function boxEdges(min, max) {
  const corner = (i) => [0, 1, 2].map((k) => ((i >> k) & 1 ? max[k] : min[k]));
  const out = [];
  for (let i = 0; i < 8; i++) {
    for (const axis of [1, 2, 4]) if (!(i & axis)) out.push(...corner(i), ...corner(i | axis));
  }
  return new Float32Array(out);
}

/**
 * The box walls of a scene document (`boundaries` of kind `box`), as line endpoints.
 * @param {{boundaries?: {kind: string, min?: number[], max?: number[]}[]}|null} scene
 * @returns {Float32Array}
 */
export function wallLines(scene) {
  const boxes = (scene?.boundaries ?? []).filter((b) => b.kind === 'box');
  const out = new Float32Array(boxes.length * 72);
  boxes.forEach((b, i) => out.set(boxEdges(b.min, b.max), i * 72));
  return out;
}

/** Draws line segments in a WebGL2 context. */
export class Outline {
  constructor(gl) {
    this.gl = gl;
    this.program = program(gl, VERT, FRAG);
    this.u = { proj: gl.getUniformLocation(this.program, 'u_proj'), view: gl.getUniformLocation(this.program, 'u_view') };
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    this.buf = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buf);
    const loc = gl.getAttribLocation(this.program, 'a_pos');
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
    this.count = 0;
  }

  /** New segments: endpoints as x, y, z triples (see {@link wallLines}). */
  set(lines) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.buf);
    gl.bufferData(gl.ARRAY_BUFFER, lines, gl.STATIC_DRAW);
    this.count = lines.length / 3;
  }

  /** Draws with the camera's matrices. */
  draw(proj, view) {
    if (this.count === 0) return;
    const gl = this.gl;
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(this.u.proj, false, proj);
    gl.uniformMatrix4fv(this.u.view, false, view);
    gl.bindVertexArray(this.vao);
    gl.drawArrays(gl.LINES, 0, this.count);
  }
}
