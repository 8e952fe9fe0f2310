/**
 * Colouring particles by a channel: the modes offered come from a list of channels
 * (`{name, unit, components}`, as a scene describes what it can stream), a vector channel by
 * its magnitude. A mode's value is the channel's name, which is also what the WebSocket's
 * `channels` parameter asks for.
 * @module
 */

/** What scenes stream today, when a scene does not list its channels. */
export const DEFAULT_CHANNELS = Object.freeze([
  { name: 'velocity', unit: 'm/s', components: 3 },
  { name: 'density', unit: 'kg/m³', components: 1 },
  { name: 'pressure', unit: 'Pa', components: 1 },
]);

/** Names for the magnitude of a vector channel, where it has one. */
const MAGNITUDE_NAMES = { velocity: 'speed' };

/** The mode that colours nothing. */
export const NONE = 'none';

/**
 * The colour modes for a list of channels, then "none".
 * @param {{name: string, unit?: string, components?: number}[]} channels
 * @returns {{value: string, label: string}[]}
 */
export function colourModes(channels) {
  const modes = channels.map((c) => {
    const what = (c.components ?? 1) > 1 ? (MAGNITUDE_NAMES[c.name] ?? `|${c.name}|`) : c.name;
    return { value: c.name, label: c.unit ? `${what} (${c.unit})` : what };
  });
  return [...modes, { value: NONE, label: NONE }];
}

/**
 * One value per particle of `channel` in a decoded frame (the magnitude of a vector channel),
 * or null when the frame lacks the channel. A module's channel without a row in the channel
 * table arrives under its per-scene tag (decoded as `channel <tag>`): the scene's channel list
 * gives that tag.
 * @param {{positions: Float32Array, channels: {tag?: number, name: string, components: number, values: ArrayLike<number>}[]}} frame
 *   a decoded frame (see the codec's `Frame`)
 * @param {string} channel a channel name, or {@link NONE}
 * @param {{name: string, tag?: number}[]} [sceneChannels] the scene's channels, with their tags
 * @returns {Float32Array|null}
 */
export function colourValues(frame, channel, sceneChannels = []) {
  const found = channel === NONE ? undefined : findChannel(frame, channel, sceneChannels);
  if (!found) return null;
  const data = found.values;
  const n = frame.positions.length / 3;
  const components = found.components;
  if (components === 1) return data instanceof Float32Array ? data : Float32Array.from(data);
  const out = new Float32Array(n);
  for (let i = 0; i < n; i++) {
    let sum = 0;
    for (let k = 0; k < components; k++) sum += data[components * i + k] ** 2;
    out[i] = Math.sqrt(sum);
  }
  return out;
}

/**
 * A decoded frame's channel named `channel`, found by its name or, for a module's channel
 * decoded as `channel <tag>`, by the tag the scene's channel list gives it; undefined when absent.
 * @param {{channels?: {tag?: number, name: string}[]}} frame
 * @param {string} channel
 * @param {{name: string, tag?: number}[]} [sceneChannels]
 */
export function findChannel(frame, channel, sceneChannels = []) {
  const tag = sceneChannels.find((c) => c.name === channel)?.tag;
  return frame.channels?.find((c) => c.name === channel || (tag !== undefined && c.tag === tag));
}

/**
 * The smallest and largest finite value.
 * @param {ArrayLike<number>} values
 * @returns {[number, number]} `[0, 0]` when there is none
 */
export function valueRange(values) {
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < values.length; i++) {
    const x = values[i];
    if (!Number.isFinite(x)) continue;
    if (x < lo) lo = x;
    if (x > hi) hi = x;
  }
  return lo <= hi ? [lo, hi] : [0, 0];
}
