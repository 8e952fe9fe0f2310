/**
 * Random access to the frames of a recording, for the replay timeline.
 *
 * Identity-ordered recordings (`floectl record`) hold delta frames, which decode only after the
 * frames before them, back to a keyframe (one every 30 frames by default). To reach any frame
 * quickly, {@link Player#prepare} decodes every frame once (which also checks the whole file)
 * and the player keeps the decoder's state every `checkpointEvery` frames; a seek then resumes
 * from the nearest kept state, keyframe or the frame shown before, whichever comes last before
 * the frame asked for, so it decodes at most `checkpointEvery` frames. A kept state shares the
 * frame's codes (2 bytes per particle and component, and those of the frame before it), so
 * memory is about `12 n (frames / checkpointEvery)` bytes for positions of `n` particles.
 * @module
 */

import { Decoder, readHeader } from './codec/index.js';
import { RecordingError, frameSpans } from './recording.js';

/** Seeks a recording's frames in any order. */
export class Player {
  /**
   * Indexes a recording (headers only; nothing is decoded yet).
   * @param {Uint8Array} bytes the whole file
   * @param {{checkpointEvery?: number, limits?: {maxParticles?: number, maxFrameBytes?: number}}} [options]
   * @throws {RecordingError} not a recording, a frame cut short, a header that does not read,
   *   or a first frame that is not a keyframe
   */
  constructor(bytes, { checkpointEvery = 8, limits = {} } = {}) {
    this.decoder = new Decoder(limits);
    this.spans = frameSpans(bytes, this.decoder.limits.maxFrameBytes);
    if (this.spans.length === 0) throw new RecordingError('the recording holds no frames');
    this.bytes = bytes;
    /** Each frame's header, in order. */
    this.headers = this.spans.map((s, i) => {
      try {
        return readHeader(this.#bytesOf(i), this.decoder.limits);
      } catch (e) {
        throw new RecordingError(`frame ${i}: ${e.message}`);
      }
    });
    if (!this.headers[0].keyframe) {
      throw new RecordingError('frame 0 is a delta frame: a recording must start with a keyframe');
    }
    /** Each frame's simulated time (s). */
    this.times = Float64Array.from(this.headers, (h) => h.time);
    this.checkpointEvery = checkpointEvery;
    /** @type {Map<number, object>} decoder state after frame i, for some delta frames i */
    this.states = new Map();
    /** The frame the decoder's state is after (-1: none). */
    this.at = -1;
  }

  /** @returns {number} frames in the recording */
  get length() {
    return this.spans.length;
  }

  /**
   * Decodes every frame once, in order, keeping the states seeks resume from, and finds the box
   * every frame's particles lie in (`extent`, `{min, max}` in m).
   * @param {(done: number, total: number) => void} [progress] called after each frame
   * @throws {RecordingError} naming the first frame that does not decode
   */
  prepare(progress) {
    this.decoder.reset();
    this.at = -1;
    const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < this.length; i++) {
      const { positions } = this.#decode(i);
      for (let j = 0; j < positions.length; j += 3) {
        for (let k = 0; k < 3; k++) {
          if (positions[j + k] < min[k]) min[k] = positions[j + k];
          if (positions[j + k] > max[k]) max[k] = positions[j + k];
        }
      }
      progress?.(i + 1, this.length);
    }
    this.extent = { min, max };
  }

  /**
   * Frame `k`, decoded (a fresh object each time: its arrays may be transferred).
   * @param {number} k 0 to `length - 1`
   * @returns {import('./codec/decoder.js').Frame}
   * @throws {RangeError} for a frame index outside the recording
   * @throws {RecordingError} for a frame that does not decode
   */
  frame(k) {
    if (!Number.isInteger(k) || k < 0 || k >= this.length) {
      throw new RangeError(`frame ${k}: the recording has frames 0 to ${this.length - 1}`);
    }
    if (this.headers[k].keyframe) {
      this.decoder.reset();
      return this.#decode(k);
    }
    // Walk back to a frame to resume after: the one decoded last, a kept state, or a keyframe
    // (frame 0 is one, so the walk ends).
    let from = k - 1;
    for (;;) {
      if (from === this.at) break;
      const state = this.states.get(from);
      if (state !== undefined) {
        this.decoder.restore(state);
        break;
      }
      if (this.headers[from].keyframe) {
        this.decoder.reset();
        this.#decode(from);
        break;
      }
      from -= 1;
    }
    for (let i = from + 1; i < k; i++) this.#decode(i);
    return this.#decode(k);
  }

  /** The bytes of frame `i`. */
  #bytesOf(i) {
    const { offset, length } = this.spans[i];
    return this.bytes.subarray(offset, offset + length);
  }

  /** Decodes frame `i` after the decoder's current state, keeping the state when it is due. */
  #decode(i) {
    let frame;
    try {
      frame = this.decoder.decode(this.#bytesOf(i));
    } catch (e) {
      this.at = -1;
      throw new RecordingError(`frame ${i}: ${e.message}`);
    }
    this.at = i;
    if (!this.headers[i].keyframe && i % this.checkpointEvery === 0 && !this.states.has(i)) {
      this.states.set(i, this.decoder.checkpoint());
    }
    return frame;
  }
}

/**
 * Playback: the frame to show after `elapsed` more seconds of simulated time from the start of
 * frame `index`, and the time left over towards the next. Frames are `times[i + 1] - times[i]`
 * apart; a step back in time (a reset while recording) counts as no time.
 * @param {ArrayLike<number>} times each frame's simulated time (s)
 * @param {number} index the frame shown
 * @param {number} elapsed simulated seconds since it was shown (speed times wall seconds)
 * @returns {{index: number, elapsed: number}} at the last frame, `elapsed` is 0
 */
export function advance(times, index, elapsed) {
  while (index + 1 < times.length) {
    const gap = Math.max(times[index + 1] - times[index], 0);
    if (elapsed < gap) return { index, elapsed };
    elapsed -= gap;
    index += 1;
  }
  return { index, elapsed: 0 };
}

/**
 * A playback speed (simulated seconds per wall second) from `speeds` that shows the frames at
 * about `fps` frames per second: a recording of a scene that ran far slower than real time holds
 * frames milliseconds of simulated time apart, which real time would rush through.
 * @param {ArrayLike<number>} times each frame's simulated time (s)
 * @param {readonly number[]} speeds the speeds offered, ascending
 * @param {number} [fps]
 * @returns {number} the largest offered speed not above the one wanted (the smallest if none),
 *   and not above 1
 */
export function naturalSpeed(times, speeds, fps = 30) {
  const n = times.length;
  const span = n > 1 ? times[n - 1] - times[0] : 0;
  const wanted = Math.min(1, span > 0 ? (span / (n - 1)) * fps : 1);
  return speeds.filter((s) => s <= wanted).at(-1) ?? speeds[0];
}
