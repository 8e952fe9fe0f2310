/**
 * Each material drawn in its own look when no channel colours the particles. The server sends
 * each material's look with the scene (`SceneInfo.materials[].look`); a scene whose materials
 * differ in look streams each particle's material (`material`), so the page asks for it and
 * draws every particle in its material's look: the ice bunny of `ice_melting` as ice in its
 * water, not as more water. A scene where ice melts also streams each particle's liquid fraction
 * (`liquid_fraction`, 0 solid to 1 melted), and a particle of a look other than water's is drawn
 * between its look and water's by it: ice as ice, the melting ones in between. Materials drawn
 * as water (a glass's water, the melt) are water whatever their fraction says (materials that
 * never change phase carry 0).
 *
 * The renderer (render.js) takes one value a particle, its look code: the look's index in the
 * scene's looks ({@link sceneLooks}) plus how far towards water, in one float
 * ({@link lookCode}), decoded by the particle shader ({@link LOOK_GLSL}). The first look is the
 * scene's body: the surface view draws it as its surface (water as water, snow white and
 * opaque) and the particles of the other looks as spheres in their look over it
 * ({@link splitByLook}).
 * @module
 */

import { NONE, findChannel } from './colour.js';

/**
 * How a look is drawn: its RGB (0 to 1), and how opaque the surface view draws a body of it
 * (0: water, shaded by the depth of water a ray crosses; 1 a matte, opaque body; between, a
 * glossy body that lets that much of what is behind it through).
 */
export const LOOKS = Object.freeze({
  water: { rgb: [0.25, 0.55, 0.9], opacity: 0 },
  snow: { rgb: [0.93, 0.95, 0.98], opacity: 1 },
  ice: { rgb: [0.78, 0.88, 0.96], opacity: 0.85 },
  solid: { rgb: [0.6, 0.6, 0.62], opacity: 1 },
});

/** Looks a scene may use at most: the shader's table holds every look. */
export const MAX_LOOKS = Object.keys(LOOKS).length;

/** The material index channel. */
export const MATERIAL = 'material';

/** The channel a melting scene streams the liquid fraction on. */
export const LIQUID_FRACTION = 'liquid_fraction';

/**
 * The scene's looks, each once, by name: water's first where a material is drawn as water
 * (the body of a scene of water and ice is its water), else the first material's; a look the
 * page does not know is drawn as water.
 * @param {{look?: string}[]|null} [materials] the scene's materials (`SceneInfo.materials`)
 * @returns {string[]} at least one name
 */
export function sceneLooks(materials) {
  const names = (materials ?? []).map(lookOf);
  return names.length ? [...new Set(names.includes('water') ? ['water', ...names] : names)] : ['water'];
}

/** A material's look, by name (water for none or one the page does not know). */
function lookOf(material) {
  return material?.look && LOOKS[material.look] ? material.look : 'water';
}

/**
 * The channels the page asks for to draw each material in its look: with no colour map chosen
 * and materials of more than one look, the material and, where the scene streams it, the
 * liquid fraction; otherwise none.
 * @param {string} colour the colour mode (a channel name, or `'none'`)
 * @param {{name: string}[]} [sceneChannels] the channels the scene can stream
 * @param {{look?: string}[]} [materials] the scene's materials
 * @returns {string[]}
 */
export function lookChannels(colour, sceneChannels = [], materials = []) {
  if ((colour && colour !== NONE) || sceneLooks(materials).length < 2) return [];
  const streamed = (name) => sceneChannels.some((c) => c.name === name);
  return streamed(MATERIAL) ? [MATERIAL, LIQUID_FRACTION].filter(streamed) : [];
}

/**
 * A particle's look code: the look's index `k` and how far towards water `f` (0 to 1) in one
 * float, `k + 0.1 + 0.8 f`, so the integer part is the index however the value is rounded.
 * @param {number} k @param {number} f
 */
export function lookCode(k, f) {
  return k + 0.1 + 0.8 * Math.min(Math.max(f, 0), 1);
}

/** The look index and fraction of a code ({@link lookCode}); what {@link LOOK_GLSL} computes. */
export function decodeLook(code) {
  const k = Math.floor(code);
  return { k, f: Math.min(Math.max((code - k - 0.1) / 0.8, 0), 1) };
}

/**
 * GLSL: the colour of a look code (`lookColour(code)`) from the scene's looks' colours
 * (`u_looks`) and water's (`u_water`), as {@link decodeLook}.
 */
export const LOOK_GLSL = `
uniform vec3 u_looks[${MAX_LOOKS}];
uniform vec3 u_water;
vec3 lookColour(float code) {
  int k = clamp(int(floor(code)), 0, ${MAX_LOOKS - 1});
  float f = clamp((code - floor(code) - 0.1) / 0.8, 0.0, 1.0);
  return mix(u_looks[k], u_water, f);
}`;

/**
 * Each particle's look code, or null when the frame lacks the material channel.
 * @param {object} frame a decoded frame
 * @param {{look?: string}[]} materials the scene's materials (`SceneInfo.materials`)
 * @param {{name: string, tag?: number}[]} [sceneChannels]
 * @returns {Float32Array|null}
 */
export function lookValues(frame, materials, sceneChannels = []) {
  const material = findChannel(frame, MATERIAL, sceneChannels);
  if (!material) return null;
  const beta = findChannel(frame, LIQUID_FRACTION, sceneChannels);
  const looks = sceneLooks(materials);
  const index = (materials ?? []).map((m) => Math.max(looks.indexOf(lookOf(m)), 0));
  const water = (materials ?? []).map((m) => lookOf(m) === 'water');
  const n = frame.positions.length / 3;
  const out = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    const m = material.values[i];
    out[i] = lookCode(index[m] ?? 0, water[m] || !beta ? 0 : beta.values[i]);
  }
  return out;
}

/**
 * The particles of the first look (the body the surface view draws as its surface) and the
 * others, with their codes (drawn as spheres over it).
 * @param {Float32Array} positions x, y, z interleaved
 * @param {Float32Array} codes one look code a particle
 * @returns {{body: {positions: Float32Array}, over: {positions: Float32Array, values: Float32Array}}}
 */
export function splitByLook(positions, codes) {
  let over = 0;
  for (let i = 0; i < codes.length; i++) if (codes[i] >= 1) over += 1;
  const body = new Float32Array(3 * (codes.length - over));
  const overPositions = new Float32Array(3 * over), overCodes = new Float32Array(over);
  let b = 0, o = 0;
  for (let i = 0; i < codes.length; i++) {
    const p = positions.subarray(3 * i, 3 * i + 3);
    if (codes[i] >= 1) {
      overPositions.set(p, 3 * o);
      overCodes[o++] = codes[i];
    } else {
      body.set(p, 3 * b++);
    }
  }
  return { body: { positions: body }, over: { positions: overPositions, values: overCodes } };
}
