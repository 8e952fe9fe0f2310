// The scene's sets besides its SPH particles and their parts (`SceneInfo.sets`): a module's own
// particles (the tracer's probes, snowflakes) and its grids (a field on regular cells, sent as grid frames).
// Each streams on a WebSocket of its own with its set's first channel (and a grid's surface
// channel, the cells' heights, where the set names one), decoded here on the page, and is drawn
// by the renderer (others.js) with the scene's particles, in the set's look where it has one.

import { Decoder } from './codec/index.js';

/** Frames per second asked for each other set: they are small and change slowly. */
const FPS = 10;

/** The latest frame of each of a scene's other sets, as they arrive. */
export class OtherSets {
  /** @param {(sets: OtherSets) => void} onFrame called after each frame decoded */
  constructor(onFrame) {
    this.onFrame = onFrame;
    /** @type {Map<string, {socket: WebSocket, decoder: Decoder, frame: object|null, grid: boolean}>} */
    this.sets = new Map();
  }

  /**
   * Streams every set of `scene` but its particles: `url(set, channels)` is the WebSocket URL of
   * a set's frames, `protocols` the sockets' subprotocols (credentials).
   */
  open(scene, url, protocols) {
    this.close();
    for (const set of scene.sets ?? []) {
      // The particles and their parts (a solid's, the fluid's) are the main stream's.
      if (set.index === 0 || set.part_of) continue;
      const surface = set.surface || '', shade = set.shade || '';
      const channel = (scene.channels ?? []).find((c) => c.set === set.name && c.name !== surface && c.name !== shade)?.name ?? '';
      const socket = new WebSocket(url(set.name, [channel, surface, shade].filter(Boolean).join(',')), protocols);
      socket.binaryType = 'arraybuffer';
      // Frames name a module's channels by per-scene tags: the scene's info maps them.
      const tag = (name) => (scene.channels ?? []).find((c) => c.set === set.name && c.name === name)?.tag ?? -1;
      const entry = {
        socket, decoder: new Decoder(), frame: null, grid: set.grid === true, channelTag: tag(channel),
        surfaceTag: surface ? tag(surface) : -1, shadeTag: shade ? tag(shade) : -1, look: set.look || '',
      };
      socket.onmessage = (e) => {
        if (typeof e.data === 'string') return;
        entry.frame = entry.decoder.decode(e.data);
        this.onFrame(this);
      };
      this.sets.set(set.name, entry);
    }
  }

  /** Closes every set's stream. */
  close() {
    for (const { socket } of this.sets.values()) socket.close();
    this.sets.clear();
  }

  /**
   * What to draw: per set with a frame, its name, whether it is a grid, its positions or grid,
   * its channel's values (one per particle or cell, vectors by magnitude), a grid's cell heights
   * (from its surface channel, else null), its shades (0 to 1 per cell, from its shade channel,
   * else null) and its look ('' for none).
   */
  drawable() {
    const out = [];
    for (const [name, { frame, grid, channelTag, surfaceTag, shadeTag, look }] of this.sets) {
      if (!frame) continue;
      const n = frame.header.particleCount;
      const tagged = (tag) => frame.channels.find((c) => c.tag === tag) ?? null;
      const c = tagged(channelTag) ?? frame.channels.find((k) => k.tag !== surfaceTag && k.tag !== shadeTag) ?? null;
      let values = null;
      if (c) {
        values = new Float32Array(n);
        for (let i = 0; i < n; i++) {
          let s = 0;
          for (let k = 0; k < c.components; k++) s += c.values[c.components * i + k] ** 2;
          values[i] = c.components === 1 ? c.values[i] : Math.sqrt(s);
        }
      }
      const heights = surfaceTag >= 0 ? tagged(surfaceTag)?.values ?? null : null;
      const shades = shadeTag >= 0 ? tagged(shadeTag)?.values ?? null : null;
      out.push({
        name, grid: grid ? frame.grid : null, positions: frame.positions, values, heights, shades, look,
        step: frame.header.step,
      });
    }
    return out;
  }

  /** One line per set for the stats overlay: name, cells or particles, the step of its frame. */
  summary() {
    return this.drawable().map((s) => `${s.name.padEnd(10)} ${s.grid
      ? `${s.grid.dims.join(' x ')} cells` : `${s.positions.length / 3} particles`} (step ${s.step})`);
  }
}

export { FPS };
