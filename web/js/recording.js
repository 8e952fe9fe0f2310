/**
 * Recordings: encoded frames in a file, the layout `floectl record` writes
 * (`client/src/recording.rs`): magic `FLOEREC1`, then per frame a little-endian u32 length and
 * the frame's bytes (the Floe frame format). The page's Record button writes the same layout,
 * so either replays here and in `floectl export --recording`.
 * @module
 */

import { DEFAULT_LIMITS, readHeader } from './codec/index.js';

/** The first eight bytes of a recording. */
export const MAGIC = 'FLOEREC1';
const MAGIC_BYTES = new TextEncoder().encode(MAGIC);
const LENGTH_BYTES = 4;

/** A file that is not a whole recording; the message names what is wrong and where. */
export class RecordingError extends Error {
  constructor(message) {
    super(message);
    this.name = 'RecordingError';
  }
}

/**
 * Where each frame of a recording lies, checking the magic and that every frame is whole (a
 * recording cut short names the frame it ends in, as the Rust reader refuses it).
 * @param {Uint8Array} bytes the whole file
 * @param {number} [maxFrameBytes] the largest frame accepted
 * @returns {{offset: number, length: number}[]} one span per frame, in order
 * @throws {RecordingError}
 */
export function frameSpans(bytes, maxFrameBytes = DEFAULT_LIMITS.maxFrameBytes) {
  if (bytes.length < MAGIC_BYTES.length || MAGIC_BYTES.some((b, i) => bytes[i] !== b)) {
    throw new RecordingError(`not a Floe recording (no ${MAGIC} header)`);
  }
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const spans = [];
  let at = MAGIC_BYTES.length;
  while (at < bytes.length) {
    const frame = spans.length;
    if (bytes.length - at < LENGTH_BYTES) {
      throw new RecordingError(`frame ${frame}: the file ends inside its length (${bytes.length - at} of 4 bytes)`);
    }
    const length = view.getUint32(at, true);
    at += LENGTH_BYTES;
    if (length > maxFrameBytes) {
      throw new RecordingError(`frame ${frame} declares ${length} bytes, more than the limit of ${maxFrameBytes}`);
    }
    if (bytes.length - at < length) {
      throw new RecordingError(`frame ${frame} declares ${length} bytes, but the file ends after ${bytes.length - at}`);
    }
    spans.push({ offset: at, length });
    at += length;
  }
  return spans;
}

/**
 * Builds a recording from frames as they arrive. A recording must start with a keyframe (delta
 * frames decode only after the frames before them), so frames before the first keyframe are
 * left out.
 */
export class RecordingWriter {
  /** @param {number} [maxBytes] the recording stops taking frames at this size */
  constructor(maxBytes = 1 << 30) {
    /** @type {Uint8Array[]} */
    this.parts = [MAGIC_BYTES];
    /** Frames taken. */
    this.frames = 0;
    /** Bytes of the file so far. */
    this.bytes = MAGIC_BYTES.length;
    this.maxBytes = maxBytes;
  }

  /** Whether the next frame would make the file larger than its limit. */
  full(frameBytes) {
    return this.bytes + LENGTH_BYTES + frameBytes > this.maxBytes;
  }

  /**
   * Appends one encoded frame (kept as given: pass a copy if the buffer is transferred later).
   * @param {Uint8Array} frame
   * @returns {boolean} whether it was taken (not before the first keyframe, nor past the limit)
   */
  push(frame) {
    if (this.frames === 0 && !readHeader(frame).keyframe) return false;
    if (this.full(frame.length)) return false;
    const length = new Uint8Array(LENGTH_BYTES);
    new DataView(length.buffer).setUint32(0, frame.length, true);
    this.parts.push(length, frame);
    this.frames += 1;
    this.bytes += LENGTH_BYTES + frame.length;
    return true;
  }

  /** @returns {Blob} the file */
  blob() {
    return new Blob(this.parts, { type: 'application/octet-stream' });
  }
}
