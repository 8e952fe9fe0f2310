// WebGL2 particle renderer: each particle is a point sprite shaded as a lit
// sphere impostor (Blinn-Phong), coloured by a scalar through a colour map; the scene's box
// walls are drawn as lines (outline.js).

import { program } from './gl.js';
import { Outline } from './outline.js';

const VERT = `#version 300 es
uniform mat4 u_proj, u_view;
uniform float u_radius, u_viewport_h;
uniform vec2 u_range;
in vec3 a_pos;
in float a_value;
out float v_t;
out vec3 v_center;
void main() {
  vec4 view = u_view * vec4(a_pos, 1.0);
  v_center = view.xyz;
  gl_Position = u_proj * view;
  gl_PointSize = max(1.0, u_radius * u_proj[1][1] * u_viewport_h / -view.z);
  v_t = clamp((a_value - u_range.x) / max(u_range.y - u_range.x, 1e-20), 0.0, 1.0);
}`;

const FRAG = `#version 300 es
precision highp float;
uniform bool u_coloured;
in float v_t;
in vec3 v_center;
out vec4 colour;
vec3 ramp(float t) {
  // A perceptual blue-green-yellow ramp (close to viridis).
  vec3 a = vec3(0.267, 0.005, 0.329), b = vec3(0.128, 0.567, 0.551), c = vec3(0.993, 0.906, 0.144);
  return t < 0.5 ? mix(a, b, t * 2.0) : mix(b, c, t * 2.0 - 1.0);
}
void main() {
  vec2 p = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  vec3 n = vec3(p.x, -p.y, sqrt(1.0 - r2));
  vec3 l = normalize(vec3(0.4, 0.7, 0.6));
  vec3 h = normalize(l + vec3(0.0, 0.0, 1.0));
  vec3 base = u_coloured ? ramp(v_t) : vec3(0.25, 0.55, 0.9);
  float diffuse = max(dot(n, l), 0.0), specular = pow(max(dot(n, h), 0.0), 48.0);
  colour = vec4(base * (0.25 + 0.75 * diffuse) + vec3(0.35) * specular, 1.0);
}`;

/** Draws particles into a canvas. */
export class Renderer {
  constructor(canvas) {
    // preserveDrawingBuffer lets tests and screenshots read the drawn pixels back.
    const gl = canvas.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
    if (!gl) throw new Error('WebGL2 is not available in this browser');
    this.gl = gl;
    this.canvas = canvas;
    const p = program(gl, VERT, FRAG);
    this.program = p;
    /** The scene's walls; `outline.set(wallLines(scene))` when the scene changes. */
    this.outline = new Outline(gl);
    this.u = Object.fromEntries(['u_proj', 'u_view', 'u_radius', 'u_viewport_h', 'u_range', 'u_coloured']
      .map((n) => [n, gl.getUniformLocation(p, n)]));
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    this.posBuf = gl.createBuffer();
    this.valBuf = gl.createBuffer();
    for (const [buf, name, size] of [[this.posBuf, 'a_pos', 3], [this.valBuf, 'a_value', 1]]) {
      const loc = gl.getAttribLocation(p, name);
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
    }
    this.count = 0;
    this.radius = 0.01;
    this.range = [0, 1];
    this.coloured = false;
  }

  /** New particle data: positions (x,y,z interleaved) and one value per particle (or null). */
  upload(positions, values) {
    const gl = this.gl;
    this.count = positions.length / 3;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.posBuf);
    gl.bufferData(gl.ARRAY_BUFFER, positions, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.valBuf);
    gl.bufferData(gl.ARRAY_BUFFER, values ?? new Float32Array(this.count), gl.DYNAMIC_DRAW);
    this.coloured = values != null;
  }

  /** Draws with the camera's matrices. */
  draw(proj, view) {
    const gl = this.gl, c = this.canvas;
    const w = c.clientWidth * devicePixelRatio, h = c.clientHeight * devicePixelRatio;
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
    gl.viewport(0, 0, w, h);
    gl.clearColor(0.063, 0.078, 0.094, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(this.u.u_proj, false, proj);
    gl.uniformMatrix4fv(this.u.u_view, false, view);
    gl.uniform1f(this.u.u_radius, this.radius);
    gl.uniform1f(this.u.u_viewport_h, h / 2);
    gl.uniform2f(this.u.u_range, this.range[0], this.range[1]);
    gl.uniform1i(this.u.u_coloured, this.coloured ? 1 : 0);
    gl.bindVertexArray(this.vao);
    gl.drawArrays(gl.POINTS, 0, this.count);
    this.outline.draw(proj, view);
  }
}
