/**
 * Ice and water drawn as themselves. A scene where a solid melts streams each particle's
 * liquid fraction (`liquid_fraction`, 0 solid to 1 melted) and material; with no colour map
 * chosen, the page asks for both and draws each particle between its solid look (the ice's)
 * and the water's look by how far it has melted: ice as ice, melt and water as water, the
 * melting ones in between. Materials drawn as water (the glass's water, the melt) are water
 * whatever their fraction says (materials that never change phase carry 0).
 * @module
 */

import { NONE, findChannel } from './colour.js';

/** The channel a melting scene streams the liquid fraction on. */
export const LIQUID_FRACTION = 'liquid_fraction';

/** The material index channel. */
export const MATERIAL = 'material';

/**
 * The channels the page asks for to draw phases: the material and the liquid fraction, when no
 * colour map is chosen and the scene streams a liquid fraction; otherwise none.
 * @param {string} colour the colour mode (a channel name, or `'none'`)
 * @param {{name: string}[]} [sceneChannels] the channels the scene can stream
 * @returns {string[]}
 */
export function phaseChannels(colour, sceneChannels = []) {
  if (colour && colour !== NONE) return [];
  return sceneChannels.some((c) => c.name === LIQUID_FRACTION) ? [MATERIAL, LIQUID_FRACTION] : [];
}

/**
 * How far each particle is drawn towards water (0 its own look, 1 water's), or null when the
 * frame lacks either channel.
 * @param {object} frame a decoded frame
 * @param {{name: string, look?: string}[]} materials the scene's materials (`SceneInfo.materials`)
 * @param {{name: string, tag?: number}[]} [sceneChannels]
 * @returns {Float32Array|null}
 */
export function phaseValues(frame, materials, sceneChannels = []) {
  const material = findChannel(frame, MATERIAL, sceneChannels);
  const beta = findChannel(frame, LIQUID_FRACTION, sceneChannels);
  if (!material || !beta) return null;
  const water = (materials ?? []).map((m) => (m.look ?? 'water') === 'water');
  const n = frame.positions.length / 3;
  const out = new Float32Array(n);
  for (let i = 0; i < n; i++) out[i] = water[material.values[i]] ? 1 : Math.min(Math.max(beta.values[i], 0), 1);
  return out;
}

/**
 * The two looks a melting scene's particles are drawn between: the first material's that is
 * not drawn as water (the ice's), and water's; null when every material is drawn as water.
 * @param {{look?: string}[]} materials
 * @param {Record<string, {rgb: number[]}>} looks the renderer's looks by name
 * @returns {{from: number[], to: number[]}|null}
 */
export function phaseLooks(materials, looks) {
  const solid = (materials ?? []).find((m) => m.look && m.look !== 'water' && looks[m.look]);
  return solid ? { from: looks[solid.look].rgb, to: looks.water.rgb } : null;
}
