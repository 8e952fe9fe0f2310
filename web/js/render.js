// WebGL2 particle renderer with two views: spheres (each particle a point sprite shaded as a lit
// sphere impostor, Blinn-Phong, coloured by a scalar through a colour map, for inspection, or in
// its material's look, looks.js; in a scene of oriented particles each is drawn as its ellipsoid
// instead, of the scene's radii and turned by the orientation the stream carries, ellipsoid.js)
// and the fluid's surface (surface.js, spheres whatever the particles' orientation, with the
// particles of a scene's other looks as spheres over it); particles hidden deep inside the
// fluid are left out or merged (cull.js). Both draw spheres at the particles' physical size
// (spacing.js); the scene's box walls are lines (outline.js), its floor a checkerboard
// (floor.js), its terrains lit meshes (terrain.js) and its other sets, grids and a module's own
// particles, tiles and points (others.js).

import { CELL, cubeLumps, cubesOf, innerCubes, lumpedParticles, outerParticles } from './cull.js';
import { ELLIPSOID_POINT, ELLIPSOID_VERT, boundingRadius } from './ellipsoid.js';
import { ATTRIBUTES, programWith } from './gl.js';
import { Floor } from './floor.js';
import { LOOKS, LOOK_GLSL, MAX_LOOKS, splitByLook } from './looks.js';
import { Others } from './others.js';
import { Outline } from './outline.js';
import { Resolution } from './resolution.js';
import { physicalRadius } from './spacing.js';
import { SPHERE_POINT, SPRITE_VERT } from './sprite.js';
import { Surface, pixelsAcross } from './surface.js';
import { TerrainMeshes } from './terrain.js';

/**
 * The particle fragment shader: `inputs` declares the surface's GLSL (its varyings and its
 * point function), `point` sets `vec3 n`, the view-space normal under the fragment, or discards.
 */
const shaded = (inputs, point) => `#version 300 es
precision highp float;
uniform bool u_coloured;
// Each particle in its material's look (looks.js): v_t times MAX_LOOKS is its look code.
uniform bool u_by_look;
in float v_t;
out vec4 colour;
${inputs}
${LOOK_GLSL}
vec3 ramp(float t) {
  // A perceptual blue-green-yellow ramp (close to viridis).
  vec3 a = vec3(0.267, 0.005, 0.329), b = vec3(0.128, 0.567, 0.551), c = vec3(0.993, 0.906, 0.144);
  return t < 0.5 ? mix(a, b, t * 2.0) : mix(b, c, t * 2.0 - 1.0);
}
void main() {
  vec3 n;
  // Depth is the sprite's (the particle centre's): writing each fragment's sphere depth would
  // switch off early depth tests, which halves the frame rate on software GL.
  ${point}
  vec3 l = normalize(vec3(0.4, 0.7, 0.6));
  vec3 h = normalize(l + vec3(0.0, 0.0, 1.0));
  vec3 base = u_by_look ? lookColour(v_t * float(${MAX_LOOKS})) : u_coloured ? ramp(v_t) : u_looks[0];
  float diffuse = max(dot(n, l), 0.0), specular = pow(max(dot(n, h), 0.0), 48.0);
  colour = vec4(base * (0.25 + 0.75 * diffuse) + vec3(0.35) * specular, 1.0);
}`;

/** Spheres: the particles of every scene but those of oriented particles. */
const FRAG = shaded(`in float v_radius;
in vec3 v_center;
${SPHERE_POINT}`, 'spherePoint(v_center, v_radius, n);');

/** Ellipsoids: oriented particles (ellipsoid.js). */
const ELLIPSOID_FRAG = shaded(ELLIPSOID_POINT, 'ellipsoidPoint(n);');

/** The background colour (the page's), linear 0-1 RGB. */
export const BACKGROUND = [0.063, 0.078, 0.094];

/**
 * Below this many pixels per particle spacing (in the surface passes' resolution) the surface
 * view draws cubes of particles: on software GL, passing over 200k points costs half a frame,
 * and a lump of two spacings then spans at most four pixels, which the smoothing irons out.
 */
const FAR_PIXELS = 2;

/** A vertex array of particles' positions and values, with its two buffers. */
function particleArrays(gl) {
  const vao = gl.createVertexArray(), posBuf = gl.createBuffer(), valBuf = gl.createBuffer();
  gl.bindVertexArray(vao);
  for (const [buf, loc, size] of [[posBuf, ATTRIBUTES.position, 3], [valBuf, ATTRIBUTES.value, 1]]) {
    gl.bindBuffer(gl.ARRAY_BUFFER, buf);
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
  }
  gl.bindVertexArray(null);
  return { vao, posBuf, valBuf };
}

/** The views a renderer can draw. */
export const VIEWS = Object.freeze(['surface', 'spheres']);

/** Draws particles into a canvas. */
export class Renderer {
  constructor(canvas) {
    // preserveDrawingBuffer lets tests and screenshots read the drawn pixels back.
    const gl = canvas.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
    if (!gl) throw new Error('WebGL2 is not available in this browser');
    this.gl = gl;
    this.canvas = canvas;
    this.spheres = programWith(gl, SPRITE_VERT, FRAG,
      ['u_proj', 'u_view', 'u_radius', 'u_viewport_h', 'u_range', 'u_coloured', 'u_by_look', 'u_looks', 'u_water', 'u_scaled']);
    /** The scene's walls; `outline.set(wallLines(scene))` when the scene changes. */
    this.outline = new Outline(gl);
    /** The scene's floor; `floor.set(min, max)` when the scene changes. */
    this.floor = new Floor(gl);
    /** The scene's terrains; `setTerrain(list)` when they arrive. */
    this.terrain = new TerrainMeshes(gl);
    /** The scene's other sets; `setOthers(sets)` as their frames arrive. */
    this.others = new Others(gl);
    // The particles' vertex array and its buffers: `vao`, `posBuf`, `valBuf`.
    Object.assign(this, particleArrays(gl));
    /**
     * In the surface view of a scene of several looks, the particles of the looks after the
     * first, drawn as spheres over the first's surface (looks.js): their arrays and how many.
     */
    this.over = { ...particleArrays(gl), count: 0 };
    /**
     * The ellipsoid program and its vertex array (the particles' buffers and a quaternion's),
     * made when a scene of oriented particles is first drawn (a scene without them pays
     * nothing); false where it cannot be made (oriented particles are then drawn as spheres).
     */
    this.ellipsoids = null;
    /** The oriented particles' ellipsoid radii (m), or null when the scene has none. */
    this.radii = null;
    /**
     * Particles in the frame, and those in the main buffers (the sphere view leaves out hidden
     * ones, the surface view merges them); `over` counts its own.
     */
    this.count = 0;
    this.mainCount = 0;
    this.box = { min: [0, 0, 0], max: [0, 0, 0] };
    /**
     * The frame's particles and, kept with them, what each view draws of them (`drawable`, made
     * when needed, cull.js), and their split by look for the surface view (`split`).
     */
    this.frame = null;
    /** Which the buffers hold: `'spheres'`, `'surface'` or `'surface-far'` (see #buffer). */
    this.buffered = null;
    /** Particle spacing (m) and drawing radius of a particle (m). */
    this.spacing = 0.01;
    this.radius = physicalRadius(this.spacing);
    this.range = [0, 1];
    this.coloured = false;
    /** Whether the values are look codes (looks.js) in place of a colour map. */
    this.byLook = false;
    /**
     * The scene's looks (LOOKS entries, looks.js's `sceneLooks`): without a colour map every
     * particle is drawn in the first, or with look codes each in its own; the surface view
     * draws the first as the body.
     */
    this.looks = [LOOKS.water];
    /** `'surface'` or `'spheres'`. */
    this.view = 'spheres';
    /** @type {Surface|null} made when first drawn */
    this.surface = null;
    /** Counts changes of particles and scene, so a frame is drawn only when something changed. */
    this.version = 0;
    this.drawn = null;
    /** Picks the resolution of each frame (a fraction of the canvas's, per axis). */
    this.resolution = new Resolution();
  }

  /** A new scene: its walls and floor (see outline.js, floor.js) and the particle spacing (m). */
  setScene(walls, floorMin, floorMax, spacing) {
    this.outline.set(walls);
    this.floor.set(floorMin, floorMax);
    this.spacing = spacing;
    this.radius = physicalRadius(spacing);
    // What is drawn of the particles depends on the spacing.
    if (this.frame) this.frame = { ...this.frame, drawable: null, split: null };
    this.buffered = null;
    this.version += 1;
  }

  /** The scene's looks, LOOKS entries, the body's first (looks.js's `sceneLooks`). */
  setLooks(looks) {
    this.looks = looks;
    this.version += 1;
  }

  /** The scene's terrains, as `GET /api/v1/scenes/{id}/terrain` lists them ([] for none). */
  setTerrain(terrains) {
    this.terrain.set(terrains);
    this.version += 1;
  }

  /** The scene's other sets (`OtherSets.drawable()`, sets.js), drawn under the particles' view. */
  setOthers(sets) {
    this.others.set(sets, LOOKS.solid.rgb);
    this.version += 1;
  }

  /** Shows or hides the other sets. */
  showOthers(visible) {
    this.others.visible = visible;
    this.version += 1;
  }

  /** Why the surface view cannot be drawn here, or null when it can. */
  surfaceUnsupported() {
    return Surface.unsupported(this.gl);
  }

  /**
   * A scene's oriented particles: the radii (m) of each one's ellipsoid, or null for a scene
   * without them (its particles are spheres, whatever frames carry).
   */
  setOriented(radii) {
    this.radii = radii ? [...radii] : null;
    this.buffered = null;
    this.version += 1;
  }

  /** Particles drawn, of those in the frame. */
  get drawnCount() {
    return this.mainCount + this.over.count;
  }

  /** Whether the sphere view draws the frame's particles as ellipsoids. */
  get oriented() {
    return this.radii !== null && this.frame?.orientations != null && this.ellipsoids !== false;
  }

  /**
   * New particle data: positions (x,y,z interleaved), one value per particle (or null) and, in a
   * scene of oriented particles, their quaternions (x,y,z,w interleaved; or null). With `byLook`
   * the values are look codes (looks.js), not a colour map.
   */
  upload(positions, values, orientations = null, byLook = false) {
    this.count = positions.length / 3;
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < positions.length; i += 3) {
      for (let k = 0; k < 3; k++) {
        const x = positions[i + k];
        if (x < min[k]) min[k] = x;
        if (x > max[k]) max[k] = x;
      }
    }
    /** The particles' bounding box (m). */
    this.box = { min, max };
    this.frame = { positions, values, orientations, drawable: null, split: null };
    this.buffered = null;
    this.coloured = values != null && !byLook;
    this.byLook = values != null && byLook;
    this.version += 1;
  }

  /**
   * Fills the buffers with what is drawn (`kind`): for `'spheres'` the particles outside inner
   * cubes and their values; for `'ellipsoids'` every particle, its value and its quaternion
   * (cull.js's reckoning that outer particles hide inner ones holds for spheres of a particle's
   * volume, not for thinner ellipsoids); for `'surface'` the outer particles and one sphere per
   * inner cube, for `'surface-far'` one sphere per cube, with radius scales in place of values.
   * With look codes the surface view's are those of the first look's particles, and the other
   * looks' particles go to `over` as spheres (looks.js).
   */
  #buffer(kind) {
    if (this.buffered === kind || !this.frame) return;
    const surface = kind === 'surface' || kind === 'surface-far';
    const split = surface && this.byLook ? (this.frame.split ??= splitByLook(this.frame.positions, this.frame.values)) : null;
    this.mainCount = this.#fill(this, this.#drawable(split?.body ?? this.frame, kind));
    this.over.count = split ? this.#fill(this.over, this.#drawable(split.over, 'spheres')) : 0;
    if (kind === 'ellipsoids') {
      const gl = this.gl;
      gl.bindBuffer(gl.ARRAY_BUFFER, this.ellipsoids.quatBuf);
      gl.bufferData(gl.ARRAY_BUFFER, this.frame.orientations, gl.DYNAMIC_DRAW);
    }
    this.buffered = kind;
  }

  /** What `kind` draws of a set of particles (`{positions, values?}`), kept with the set. */
  #drawable(set, kind) {
    const { positions, values } = set;
    const d = (set.drawable ??= { grid: cubesOf(positions, this.spacing, this.box) });
    const cubes = () => (d.cubes ??= innerCubes(positions, this.spacing, this.box, d.grid));
    if (kind === 'spheres') return (d.spheres ??= outerParticles(positions, values, cubes()));
    if (kind === 'ellipsoids') return { positions, values };
    const lumps = kind === 'surface-far' ? (d.far ??= cubeLumps(positions, d.grid)) : (d.surface ??= lumpedParticles(positions, cubes()));
    return { positions: lumps.positions, values: lumps.scales };
  }

  /** Uploads particles (`{positions, values?}`) into the buffers of `arrays`; returns how many. */
  #fill(arrays, data) {
    const gl = this.gl, n = data.positions.length / 3;
    gl.bindBuffer(gl.ARRAY_BUFFER, arrays.posBuf);
    gl.bufferData(gl.ARRAY_BUFFER, data.positions, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, arrays.valBuf);
    gl.bufferData(gl.ARRAY_BUFFER, data.values ?? new Float32Array(n), gl.DYNAMIC_DRAW);
    return n;
  }

  /**
   * Draws with the camera's matrices, unless nothing has changed since the last frame drawn (the
   * canvas keeps it: with hundreds of thousands of particles on software GL a frame costs a
   * good part of a second of CPU, which the solver may share), at the resolution
   * {@link Resolution} picks (lower while the picture moves on a slow machine, full once it
   * stands still). `distance` (m), the camera's to what it looks at, sets how much the surface
   * view smooths; `now` (ms) is the animation frame's time.
   * @returns {boolean} whether it drew
   */
  draw(proj, view, distance, now = performance.now()) {
    const gl = this.gl, c = this.canvas;
    const key = [...proj, ...view, c.clientWidth, c.clientHeight, devicePixelRatio, this.view, this.version, ...this.range].join();
    const scale = this.resolution.next(now, key !== this.drawn);
    this.drawn = key;
    if (scale === null) return false;
    const w = Math.max(1, Math.round(c.clientWidth * devicePixelRatio * scale));
    const h = Math.max(1, Math.round(c.clientHeight * devicePixelRatio * scale));
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
    const surface = this.view === 'surface' && this.surfaceUnsupported() === null;
    // Seen from afar the surface view draws cubes of particles (cull.js): a spacing spans fewer
    // than FAR_PIXELS pixels of its passes where the particles come nearest the camera.
    const far = surface && pixelsAcross(this.spacing, this.box, proj, view, h * Surface.SCALE) < FAR_PIXELS;
    const ellipsoids = !surface && this.oriented ? this.#ellipsoidProgram() : null;
    this.#buffer(surface ? (far ? 'surface-far' : 'surface') : ellipsoids ? 'ellipsoids' : 'spheres');
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, w, h);
    this.#background(proj, view);
    if (surface) {
      // The other looks' spheres: behind the body's surface, where it refracts them, and then
      // in front of it, where they stand out of it (the surface wrote its depth).
      const over = (p, v, height) => this.#particles(this.spheres, this.over.vao, this.over.count, p, v, height);
      this.surface ??= new Surface(gl);
      this.surface.draw({ proj, view, vao: this.vao, count: this.mainCount, radius: this.radius,
        grain: far ? CELL * this.radius : this.radius, box: this.box, width: w, height: h, distance,
        background: (p, v, height) => { this.#background(p, v); over(p, v, height); }, look: this.looks[0] });
      over(proj, view, h);
      // Walls in front of the water.
      this.outline.draw(proj, view);
      return true;
    }
    this.#particles(ellipsoids ?? this.spheres, ellipsoids?.vao ?? this.vao, this.mainCount, proj, view, h);
    this.outline.draw(proj, view);
    return true;
  }

  /**
   * Draws `count` particles of the vertex array `vao` with `program` (the spheres' or the
   * ellipsoids') into a viewport `h` pixels high, depth-tested, coloured as the frame says.
   */
  #particles({ program, u }, vao, count, proj, view, h) {
    if (count === 0) return;
    const gl = this.gl;
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    gl.useProgram(program);
    gl.uniformMatrix4fv(u.u_proj, false, proj);
    gl.uniformMatrix4fv(u.u_view, false, view);
    gl.uniform1f(u.u_viewport_h, h);
    // Look codes reach the fragment shader as v_t, the code over MAX_LOOKS (looks.js).
    const range = this.byLook ? [0, MAX_LOOKS] : this.range;
    gl.uniform2f(u.u_range, range[0], range[1]);
    gl.uniform1i(u.u_coloured, this.coloured ? 1 : 0);
    gl.uniform1i(u.u_by_look, this.byLook ? 1 : 0);
    gl.uniform3fv(u.u_looks, Array.from({ length: MAX_LOOKS }, (_, k) => (this.looks[k] ?? this.looks[0]).rgb).flat());
    gl.uniform3fv(u.u_water, LOOKS.water.rgb);
    if (u.u_radii) {
      gl.uniform1f(u.u_radius, boundingRadius(this.radii));
      gl.uniform3fv(u.u_radii, this.radii);
    } else {
      gl.uniform1f(u.u_radius, this.radius);
      gl.uniform1i(u.u_scaled, 0);
    }
    gl.bindVertexArray(vao);
    gl.drawArrays(gl.POINTS, 0, count);
  }

  /**
   * The ellipsoid program, its vertex array (the particles' position and value buffers, and the
   * quaternions' `quatBuf`), made on first use; null where the driver refuses it (warned once).
   */
  #ellipsoidProgram() {
    if (this.ellipsoids !== null) return this.ellipsoids || null;
    const gl = this.gl;
    let e;
    try {
      e = programWith(gl, ELLIPSOID_VERT, ELLIPSOID_FRAG,
        ['u_proj', 'u_view', 'u_radius', 'u_radii', 'u_viewport_h', 'u_range', 'u_coloured', 'u_by_look', 'u_looks', 'u_water']);
    } catch (err) {
      console.warn(`oriented particles drawn as spheres: the ellipsoid shader failed: ${err.message}`);
      this.ellipsoids = false;
      return null;
    }
    e.vao = gl.createVertexArray();
    e.quatBuf = gl.createBuffer();
    gl.bindVertexArray(e.vao);
    for (const [buf, loc, size] of [[this.posBuf, ATTRIBUTES.position, 3], [this.valBuf, ATTRIBUTES.value, 1],
      [e.quatBuf, ATTRIBUTES.orientation, 4]]) {
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
    }
    gl.bindVertexArray(null);
    this.ellipsoids = e;
    return e;
  }

  /**
   * Clears the bound framebuffer to the background and draws the floor, terrains, the other sets
   * and walls.
   */
  #background(proj, view) {
    const gl = this.gl;
    gl.clearColor(...BACKGROUND, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LESS);
    this.floor.draw(proj, view);
    this.terrain.draw(proj, view);
    this.others.draw(proj, view);
    this.outline.draw(proj, view);
  }
}
