// WebGL2 helpers shared by the particle renderers, the wall outline and the floor.

function compile(gl, type, src) {
  const s = gl.createShader(type);
  gl.shaderSource(s, src);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
  return s;
}

/** A linked program from vertex and fragment shader sources; throws the driver's log. */
export function program(gl, vert, frag) {
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, vert));
  gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, frag));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  return p;
}

/** A program and the locations of the uniforms named, as `{program, u: {name: location}}`. */
export function programWith(gl, vert, frag, uniforms) {
  const p = program(gl, vert, frag);
  return { program: p, u: Object.fromEntries(uniforms.map((n) => [n, gl.getUniformLocation(p, n)])) };
}

/**
 * Particle attributes' locations, fixed in every particle shader (`layout(location = ...)`), so
 * one vertex array serves the sphere, depth and thickness programs; `orientation` (a
 * quaternion) only the ellipsoid program's, in a vertex array of its own (ellipsoid.js).
 */
export const ATTRIBUTES = Object.freeze({ position: 0, value: 1, orientation: 2 });

/**
 * A vertex shader drawing one triangle over the whole viewport (`gl.drawArrays(gl.TRIANGLES, 0, 3)`
 * with no attributes), for full-screen passes.
 */
export const FULL_SCREEN = `#version 300 es
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}`;

/**
 * A 2D texture of `w` x `h` texels of `internal` format, nearest or linear filtered, clamped.
 * @returns {WebGLTexture}
 */
export function texture(gl, w, h, internal, format, type, filter = gl.NEAREST) {
  const t = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, t);
  gl.texImage2D(gl.TEXTURE_2D, 0, internal, w, h, 0, format, type, null);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, filter);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, filter);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  return t;
}

/**
 * A framebuffer drawing into `colours` (a texture, or several: attachments 0, 1, ... in order),
 * with a depth buffer of the same size when `depth` is true; throws if the driver cannot render
 * to it.
 * @returns {WebGLFramebuffer}
 */
export function framebuffer(gl, colours, w, h, depth = false) {
  const list = Array.isArray(colours) ? colours : [colours];
  const fb = gl.createFramebuffer();
  gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
  list.forEach((t, i) => gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, t, 0));
  gl.drawBuffers(list.map((_, i) => gl.COLOR_ATTACHMENT0 + i));
  if (depth) {
    const rb = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, rb);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, w, h);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, rb);
    fb.depth = rb;
  }
  const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  if (status !== gl.FRAMEBUFFER_COMPLETE) throw new Error(`framebuffer incomplete (0x${status.toString(16)})`);
  return fb;
}
