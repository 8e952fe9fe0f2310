// The fluid's surface in screen space, after W. J. van der Laan, S. Green and M. Sainz, "Screen
// space fluid rendering with curvature flow", I3D 2009. Per frame:
//
// 1. depth: every particle as a sphere; per pixel the view distance of the nearest surface (R32F);
// 2. thickness: the spheres' chords added up per pixel (R16F, additive blending), the water a
//    ray crosses; particles are spheres of their own volume (spacing.js), so this is the depth of
//    water, on average. Where the browser blends float targets per draw buffer
//    (EXT_float_blend, OES_draw_buffers_indexed), 1 and 2 are one pass over the particles into
//    two targets, the nearest distance kept by MIN blending; else two passes, the first
//    depth-tested. Passing over a few hundred thousand points is what costs most on software GL;
// 3. smoothing: the depth image flows by its mean curvature (the paper's section 4: the curvature
//    of the surface the depth image describes, from screen-space first and second differences,
//    advanced by explicit Euler steps), which flattens single spheres' bumps but keeps silhouettes:
//    a neighbour further than a few radii in depth, or no fluid, counts as level with the pixel;
// 4. normals from the smoothed depth (of the two one-sided differences the smaller, so a
//    silhouette is not taken for a slope; a pixel whose neighbours on both sides of an axis lie
//    beyond a jump faces the camera along that axis);
// 5. shading (full resolution, the normals filtered between texels): the background refracted
//    along the normal and tinted by Beer-Lambert absorption over the thickness, light scattered
//    back in water's colour the more the thicker it is, Fresnel (Schlick) reflection of a sky,
//    and a specular highlight; a body of another look (looks.js) is its colour lit by the normal
//    instead, matte and opaque (snow), or over the refracted background with the reflection and
//    the highlight (ice).
//    The surface's depth goes to the depth buffer, so walls drawn after it hide behind it.
//
// Passes 1 to 4 run at `Surface.SCALE` times the canvas's resolution, and passes 3 to 5 only over
// the particles' bounding box on screen. On software GL (no GPU) the particle pass costs most
// (half of a frame at 200k particles, measured): seen from afar the renderer hands it one lump per
// cube of particles instead (cull.js), and `grain`, the bumps' radius, is then a lump's.
// The scene behind the water is drawn into the canvas by the caller first, and again at the
// passes' resolution for refraction by `background`, with what is seen only through the water
// there (the renderer's spheres of a scene's other looks).

import { FULL_SCREEN, framebuffer, programWith, texture } from './gl.js';
import { SPHERE_POINT, SPRITE_VERT, WINDOW_DEPTH } from './sprite.js';

/** Distance marking a pixel without fluid (the depth targets are cleared to it). */
const EMPTY = '1e30';
/** Neighbours further apart in depth than this many particle radii are across a silhouette. */
const JUMP = 6;

/**
 * The particle pass's fragment shader, writing `outputs`: `['distance', 'chord']` in one pass
 * (to two targets), `['distance']` (depth-tested: it writes gl_FragDepth) or `['chord']`.
 */
function particleFrag(outputs) {
  const out = outputs.map((name, i) => `layout(location = ${i}) out float ${name};`).join('\n');
  const depthTested = outputs.length === 1 && outputs[0] === 'distance';
  return `#version 300 es
precision highp float;
uniform mat4 u_proj;
in float v_radius;
in vec3 v_center;
${out}
${SPHERE_POINT}
void main() {
  vec3 n;
  vec3 p = spherePoint(v_center, v_radius, n);
  ${outputs.includes('distance') ? 'distance = -p.z;' : ''}
  ${outputs.includes('chord') ? 'chord = 2.0 * v_radius * n.z;' : ''}
  ${depthTested ? 'gl_FragDepth = windowDepth(u_proj, p);' : ''}
}`;
}

const SMOOTH_FRAG = `#version 300 es
precision highp float;
uniform highp sampler2D u_depth;
uniform vec2 u_c;      // the paper's C_x, C_y: -2 / (viewport size x focal length), negative for positive distances
uniform float u_jump;  // larger steps in distance (m) are silhouettes
uniform float u_rate;  // Euler step as a fraction of the largest stable one
out float distance;
float near(ivec2 q, float zc) {
  float z = texelFetch(u_depth, q, 0).r;
  return abs(z - zc) > u_jump ? zc : z;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = texelFetch(u_depth, p, 0).r;
  if (z >= ${EMPTY}) { distance = z; return; }
  float r = near(p + ivec2(1, 0), z), l = near(p - ivec2(1, 0), z);
  float t = near(p + ivec2(0, 1), z), b = near(p - ivec2(0, 1), z);
  float rt = near(p + ivec2(1, 1), z), lb = near(p - ivec2(1, 1), z);
  float rb = near(p + ivec2(1, -1), z), lt = near(p + ivec2(-1, 1), z);
  float dx = 0.5 * (r - l), dy = 0.5 * (t - b);
  float dxx = r + l - 2.0 * z, dyy = t + b - 2.0 * z, dxy = 0.25 * (rt + lb - rb - lt);
  float cx = u_c.x, cy = u_c.y, cx2 = cx * cx, cy2 = cy * cy;
  float d = cy2 * dx * dx + cx2 * dy * dy + cx2 * cy2 * z * z;
  float ddx = 2.0 * (cy2 * dx * dxx + cx2 * dy * dxy + cx2 * cy2 * z * dx);
  float ddy = 2.0 * (cy2 * dx * dxy + cx2 * dy * dyy + cx2 * cy2 * z * dy);
  float ex = 0.5 * dx * ddx - dxx * d, ey = 0.5 * dy * ddy - dyy * d;
  float h = (cy * ex + cx * ey) / (2.0 * d * sqrt(d));
  // On a level surface the flow is diffusion with coefficient dt / (2 |C| z) per pixel squared,
  // stable up to 1/4: the step scales with the distance.
  float dt = u_rate * 0.5 * min(abs(cx), abs(cy)) * z;
  distance = z + dt * h;
}`;

/** GLSL: a distance texel (clamped to the texture) and the view-space point it stands for. */
const VIEW_POINT = `
uniform highp sampler2D u_depth;
uniform mat4 u_proj;
uniform vec2 u_low;
float depthAt(ivec2 q) { return texelFetch(u_depth, clamp(q, ivec2(0), ivec2(u_low) - 1), 0).r; }
vec3 viewPoint(ivec2 q, float d) {
  vec2 ndc = (vec2(q) + 0.5) / u_low * 2.0 - 1.0;
  return vec3((ndc.x + u_proj[2][0]) * d / u_proj[0][0], (ndc.y + u_proj[2][1]) * d / u_proj[1][1], -d);
}`;

const NORMAL_FRAG = `#version 300 es
precision highp float;
${VIEW_POINT}
uniform float u_jump;  // larger steps in distance (m) are silhouettes, not slopes
out vec4 normal;       // view-space normal, and 1 where there is fluid (0 elsewhere)
vec3 tangent(ivec2 q, vec3 c, ivec2 dir) {
  float df = depthAt(q + dir), db = depthAt(q - dir);
  vec3 f = viewPoint(q + dir, df) - c, b = c - viewPoint(q - dir, db);
  bool fOut = abs(f.z) > u_jump, bOut = abs(b.z) > u_jump;
  if (fOut) return bOut ? vec3(0.0) : b;
  if (bOut) return f;
  return abs(f.z) < abs(b.z) ? f : b;
}
void main() {
  ivec2 q = ivec2(gl_FragCoord.xy);
  float d = depthAt(q);
  if (d >= ${EMPTY}) { normal = vec4(0.0); return; }
  vec3 p = viewPoint(q, d);
  vec3 n = cross(tangent(q, p, ivec2(1, 0)), tangent(q, p, ivec2(0, 1)));
  normal = vec4(dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0), 1.0);
}`;

const SHADE_FRAG = `#version 300 es
precision highp float;
${VIEW_POINT}
uniform sampler2D u_normals, u_thickness, u_background;
uniform mat4 u_view;
uniform vec2 u_size;
// The body's look: its colour and opacity (looks.js; 0 for water).
uniform vec4 u_look;
out vec4 colour;
${WINDOW_DEPTH}
vec3 sky(vec3 dir) {
  return dir.y > 0.0 ? mix(vec3(0.3, 0.36, 0.42), vec3(0.5, 0.62, 0.75), dir.y) : vec3(0.13, 0.15, 0.17);
}
void main() {
  vec2 uv = gl_FragCoord.xy / u_size;
  ivec2 q = ivec2(uv * u_low);
  float d = depthAt(q);
  if (d >= ${EMPTY}) discard;
  vec3 p = viewPoint(q, d);
  // Normals filtered between texels of the passes' resolution: smooth shading at full resolution.
  vec4 filtered = texture(u_normals, uv);
  vec3 n = dot(filtered.xyz, filtered.xyz) > 0.0 ? normalize(filtered.xyz) : vec3(0.0, 0.0, 1.0);
  vec3 v = normalize(-p);
  float thickness = texture(u_thickness, uv).r;
  // Refraction: the background seen through the water, shifted along the normal with depth.
  vec3 behind = texture(u_background, clamp(uv - n.xy * 0.04 * min(thickness * 4.0, 1.0), 0.0, 1.0)).rgb;
  // Beer-Lambert: light through the water loses red first; what the water scatters back shows
  // its own colour, more of it the thicker the water.
  vec3 tint = exp(-vec3(2.2, 0.7, 0.3) * thickness);
  float opacity = 1.0 - exp(-4.0 * thickness);
  vec3 l = normalize(vec3(0.4, 0.7, 0.6));
  float lit = 0.55 + 0.45 * max(dot(n, l), 0.0);
  gl_FragDepth = windowDepth(u_proj, p);
  if (u_look.a >= 1.0) {
    colour = vec4(u_look.rgb * lit, 1.0);
    return;
  }
  vec3 water = vec3(0.13, 0.48, 0.78) * lit;
  vec3 body = u_look.a > 0.0 ? mix(behind, u_look.rgb * lit, u_look.a) : mix(behind * tint, water, opacity);
  float cosine = max(dot(n, v), 0.0);
  float fresnel = 0.02 + 0.98 * pow(1.0 - cosine, 5.0);
  vec3 reflected = sky(transpose(mat3(u_view)) * reflect(-v, n));
  float specular = pow(max(dot(n, normalize(l + v)), 0.0), 60.0);
  colour = vec4(mix(body, reflected, fresnel) + vec3(0.5) * specular, 1.0);
}`;

/**
 * The pixels (`[x, y, width, height]`, y up, in a `w` x `h` viewport) that the box [min, max]
 * grown by `pad` covers through `proj * view` (column-major); the whole viewport when part of
 * the box is behind the eye, null when it is off screen.
 */
export function screenRect(min, max, pad, proj, view, w, h) {
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (let i = 0; i < 8; i++) {
    const p = [0, 1, 2].map((k) => ((i >> k) & 1 ? max[k] + pad : min[k] - pad));
    const v = [0, 1, 2, 3].map((r) => view[r] * p[0] + view[4 + r] * p[1] + view[8 + r] * p[2] + view[12 + r]);
    const c = [0, 1, 3].map((r) => proj[r] * v[0] + proj[4 + r] * v[1] + proj[8 + r] * v[2] + proj[12 + r] * v[3]);
    if (c[2] <= 1e-9) return [0, 0, w, h];
    const x = ((c[0] / c[2] + 1) / 2) * w, y = ((c[1] / c[2] + 1) / 2) * h;
    x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
  }
  const left = Math.max(0, Math.floor(x0) - 2), bottom = Math.max(0, Math.floor(y0) - 2);
  const right = Math.min(w, Math.ceil(x1) + 2), top = Math.min(h, Math.ceil(y1) + 2);
  return right > left && top > bottom ? [left, bottom, right - left, top - bottom] : null;
}

/**
 * Pixels that a length `l` (m) spans, in a viewport `h` pixels high through `proj * view`
 * (column-major), at the depth where the box [min, max] comes nearest the eye; Infinity when
 * part of the box is at or behind the eye.
 */
export function pixelsAcross(l, box, proj, view, h) {
  let nearest = Infinity;
  for (let i = 0; i < 8; i++) {
    const p = [0, 1, 2].map((k) => ((i >> k) & 1 ? box.max[k] : box.min[k]));
    const z = view[2] * p[0] + view[6] * p[1] + view[10] * p[2] + view[14];
    nearest = Math.min(nearest, -z);
  }
  return nearest > 0 ? (l * proj[5] * h) / (2 * nearest) : Infinity;
}

/** Screen-space fluid surface passes in a WebGL2 context. */
export class Surface {
  /** Resolution of the depth, thickness and smoothing passes, as a fraction of the canvas's. */
  static SCALE = 0.5;

  /** Why this context cannot draw the surface (it renders to float textures), or null. */
  static unsupported(gl) {
    return gl.getExtension('EXT_color_buffer_float') ? null : 'this browser cannot render to float textures (EXT_color_buffer_float)';
  }

  constructor(gl) {
    this.gl = gl;
    /** Per-buffer blending, when depth and thickness take one pass over the particles. */
    this.indexed = gl.getExtension('EXT_float_blend') ? gl.getExtension('OES_draw_buffers_indexed') : null;
    const particle = ['u_proj', 'u_view', 'u_radius', 'u_viewport_h', 'u_scaled'];
    const passes = this.indexed ? [['distance', 'chord']] : [['distance'], ['chord']];
    this.particlePasses = passes.map((outputs) => programWith(gl, SPRITE_VERT, particleFrag(outputs), particle));
    this.smoothPass = programWith(gl, FULL_SCREEN, SMOOTH_FRAG, ['u_depth', 'u_c', 'u_jump', 'u_rate']);
    this.normalPass = programWith(gl, FULL_SCREEN, NORMAL_FRAG, ['u_depth', 'u_proj', 'u_low', 'u_jump']);
    this.shadePass = programWith(gl, FULL_SCREEN, SHADE_FRAG,
      ['u_depth', 'u_normals', 'u_thickness', 'u_background', 'u_proj', 'u_view', 'u_size', 'u_low', 'u_look']);
    this.empty = gl.createVertexArray();
    this.targets = null;
  }

  /** (Re)makes the render targets for a canvas of `w` x `h`. */
  #resize(w, h) {
    const lw = Math.max(1, Math.round(w * Surface.SCALE)), lh = Math.max(1, Math.round(h * Surface.SCALE));
    const t = this.targets;
    if (t && t.w === w && t.h === h && t.lw === lw && t.lh === lh) return t;
    const gl = this.gl;
    if (t) {
      for (const x of [t.depthA, t.depthB, t.thickness, t.normals, t.background]) gl.deleteTexture(x);
      for (const f of [...t.particleFbs, t.fbA, t.fbB, t.normalsFb, t.backgroundFb]) {
        if (f.depth) gl.deleteRenderbuffer(f.depth);
        gl.deleteFramebuffer(f);
      }
    }
    const float = (filter) => texture(gl, lw, lh, gl.R32F, gl.RED, gl.FLOAT, filter);
    const depthA = float(gl.NEAREST), depthB = float(gl.NEAREST);
    const thickness = texture(gl, lw, lh, gl.R16F, gl.RED, gl.HALF_FLOAT, gl.LINEAR);
    const normals = texture(gl, lw, lh, gl.RGBA16F, gl.RGBA, gl.HALF_FLOAT, gl.LINEAR);
    const background = texture(gl, lw, lh, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, gl.LINEAR);
    this.targets = {
      w, h, lw, lh, depthA, depthB, thickness, normals, background,
      normalsFb: framebuffer(gl, normals, lw, lh),
      // One framebuffer per particle pass.
      particleFbs: this.indexed
        ? [framebuffer(gl, [depthA, thickness], lw, lh)]
        : [framebuffer(gl, depthA, lw, lh, true), framebuffer(gl, thickness, lw, lh)],
      fbA: framebuffer(gl, depthA, lw, lh),
      fbB: framebuffer(gl, depthB, lw, lh),
      backgroundFb: framebuffer(gl, background, lw, lh, true),
    };
    return this.targets;
  }

  /**
   * Draws the surface into the canvas (the default framebuffer, the scene behind it drawn
   * already), depth included.
   * @param {{proj: Float32Array, view: Float32Array, vao: WebGLVertexArrayObject, count: number,
   *   radius: number, grain: number, box: {min: number[], max: number[]}, width: number, height: number,
   *   distance: number, background: (proj: Float32Array, view: Float32Array, height: number) => void,
   *   look: {rgb: number[], opacity: number}}} o the particles (`vao` with positions and radius
   *   scales, `count`, a particle's drawing `radius` in m, bounding `box`), the canvas's size in
   *   pixels, the camera's distance to what it looks at (m; sets how much to smooth), what draws
   *   the scene behind the water (into the bound framebuffer, `height` pixels high), and the
   *   body's look (looks.js: water, or a body of that colour and opacity)
   */
  draw(o) {
    const gl = this.gl;
    const t = this.#resize(o.width, o.height);
    const rect = screenRect(o.box.min, o.box.max, o.radius, o.proj, o.view, t.lw, t.lh);
    if (rect === null || o.count === 0) return;
    // The scene behind the water, to refract.
    gl.bindFramebuffer(gl.FRAMEBUFFER, t.backgroundFb);
    gl.viewport(0, 0, t.lw, t.lh);
    o.background(o.proj, o.view, t.lh);
    // 1 and 2. Depth of the nearest sphere, and the spheres' chords added.
    gl.bindVertexArray(o.vao);
    this.#particlePasses(o, t);
    // 3. Curvature flow, ping-ponging between the two depth textures, over the particles' box
    // only: pixels outside it are never read, as the box reaches past every sphere and a pixel
    // without fluid reads no neighbour.
    gl.enable(gl.SCISSOR_TEST);
    gl.scissor(...rect);
    gl.bindVertexArray(this.empty);
    const s = this.smoothPass;
    gl.useProgram(s.program);
    gl.uniform1i(s.u.u_depth, 0);
    gl.uniform2f(s.u.u_c, -2 / (t.lw * o.proj[0]), -2 / (t.lh * o.proj[5]));
    gl.uniform1f(s.u.u_jump, JUMP * o.grain);
    gl.uniform1f(s.u.u_rate, 0.9);
    gl.activeTexture(gl.TEXTURE0);
    // The other texture holds an older frame's distances: clear it, so none is read as fluid.
    gl.bindFramebuffer(gl.FRAMEBUFFER, t.fbB);
    gl.clearBufferfv(gl.COLOR, 0, [Number(EMPTY), 0, 0, 0]);
    let src = t.depthA;
    for (let i = 0; i < this.iterations(o, t.lh); i++) {
      const [dst, fb] = src === t.depthA ? [t.depthB, t.fbB] : [t.depthA, t.fbA];
      gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
      gl.bindTexture(gl.TEXTURE_2D, src);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      src = dst;
    }
    // 4. Normals at the passes' resolution (cleared first: the shading filters across the box's edge).
    gl.bindFramebuffer(gl.FRAMEBUFFER, t.normalsFb);
    gl.disable(gl.SCISSOR_TEST);
    gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]);
    gl.enable(gl.SCISSOR_TEST);
    const nrm = this.normalPass;
    gl.useProgram(nrm.program);
    gl.bindTexture(gl.TEXTURE_2D, src);
    gl.uniform1i(nrm.u.u_depth, 0);
    gl.uniformMatrix4fv(nrm.u.u_proj, false, o.proj);
    gl.uniform2f(nrm.u.u_low, t.lw, t.lh);
    gl.uniform1f(nrm.u.u_jump, JUMP * o.grain);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    // 5. Shading into the canvas, over the particles' box in canvas pixels.
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, t.w, t.h);
    const kx = t.w / t.lw, ky = t.h / t.lh;
    gl.scissor(Math.floor(rect[0] * kx), Math.floor(rect[1] * ky), Math.ceil(rect[2] * kx), Math.ceil(rect[3] * ky));
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.ALWAYS);
    const c = this.shadePass;
    gl.useProgram(c.program);
    const inputs = [[src, c.u.u_depth], [t.normals, c.u.u_normals], [t.thickness, c.u.u_thickness], [t.background, c.u.u_background]];
    inputs.forEach(([tex, loc], unit) => {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, tex);
      gl.uniform1i(loc, unit);
    });
    gl.uniformMatrix4fv(c.u.u_proj, false, o.proj);
    gl.uniformMatrix4fv(c.u.u_view, false, o.view);
    gl.uniform2f(c.u.u_size, t.w, t.h);
    gl.uniform2f(c.u.u_low, t.lw, t.lh);
    gl.uniform4f(c.u.u_look, ...o.look.rgb, o.look.opacity);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.disable(gl.SCISSOR_TEST);
    gl.depthFunc(gl.LESS);
    // Unbind the passes' textures, so the next frame can render into them.
    for (let unit = 3; unit >= 0; unit--) {
      gl.activeTexture(gl.TEXTURE0 + unit);
      gl.bindTexture(gl.TEXTURE_2D, null);
    }
  }

  /**
   * Smoothing steps: enough for the flow to spread over one and a half grain radii in pixels
   * at the camera's distance (diffusion spreads sqrt(2 k n) pixels in n steps of coefficient k),
   * which irons out the layers of particles, within 4 to 40.
   */
  iterations(o, lowHeight) {
    const spread = (1.5 * o.grain * o.proj[5] * lowHeight) / (2 * Math.max(o.distance, 1e-6));
    return Math.max(4, Math.min(40, Math.round((spread * spread) / (2 * 0.9 * 0.25))));
  }

  /** The particle passes: into the depth and thickness targets, cleared first. */
  #particlePasses(o, t) {
    const gl = this.gl, ext = this.indexed;
    const draw = ({ program, u }) => {
      gl.useProgram(program);
      gl.uniformMatrix4fv(u.u_proj, false, o.proj);
      gl.uniformMatrix4fv(u.u_view, false, o.view);
      gl.uniform1f(u.u_radius, o.radius);
      gl.uniform1f(u.u_viewport_h, t.lh);
      gl.uniform1i(u.u_scaled, 1);
      gl.drawArrays(gl.POINTS, 0, o.count);
    };
    const [distanceFb, chordFb] = t.particleFbs;
    gl.bindFramebuffer(gl.FRAMEBUFFER, distanceFb);
    gl.clearBufferfv(gl.COLOR, 0, [Number(EMPTY), 0, 0, 0]);
    if (ext) {
      // Target 0 keeps the nearest distance, target 1 adds chords.
      gl.clearBufferfv(gl.COLOR, 1, [0, 0, 0, 0]);
      gl.disable(gl.DEPTH_TEST);
      ext.enableiOES(gl.BLEND, 0);
      ext.blendEquationiOES(0, gl.MIN);
      ext.enableiOES(gl.BLEND, 1);
      ext.blendEquationiOES(1, gl.FUNC_ADD);
      ext.blendFunciOES(1, gl.ONE, gl.ONE);
      draw(this.particlePasses[0]);
      gl.disable(gl.BLEND);
      gl.blendEquation(gl.FUNC_ADD);
      return;
    }
    gl.clear(gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    draw(this.particlePasses[0]);
    gl.bindFramebuffer(gl.FRAMEBUFFER, chordFb);
    gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]);
    gl.disable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.ONE, gl.ONE);
    draw(this.particlePasses[1]);
    gl.disable(gl.BLEND);
  }
}
