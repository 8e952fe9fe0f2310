/**
 * A bounds-checked little-endian cursor over a frame's bytes (mirrors `proto/src/reader.rs`).
 * Running past the end throws `MalformedError` naming the part being read: the caller has
 * already checked that the whole frame is present, so a read past the end means a length
 * field lied.
 * @module
 */

import { MalformedError } from './errors.js';

/** Reads fields in order from a `Uint8Array`, never outside it. */
export class Reader {
  /**
   * @param {Uint8Array} bytes the bytes to read (a view; not copied)
   * @param {string} what the part being read, for error messages
   */
  constructor(bytes, what) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.pos = 0;
    this.what = what;
  }

  /** @returns {number} bytes left */
  remaining() {
    return this.bytes.length - this.pos;
  }

  /**
   * Advances past `len` bytes and returns where they start.
   * @param {number} len
   * @returns {number} the offset of the first of them
   */
  #advance(len) {
    const at = this.pos;
    if (len > this.bytes.length - at) {
      throw new MalformedError(`${this.what} runs past its end (${len} bytes wanted at ${at})`);
    }
    this.pos = at + len;
    return at;
  }

  /**
   * The next `len` bytes, as a view into the same buffer.
   * @param {number} len
   * @returns {Uint8Array}
   */
  take(len) {
    const at = this.#advance(len);
    return this.bytes.subarray(at, at + len);
  }

  /** @param {number} len bytes to skip */
  skip(len) {
    this.#advance(len);
  }

  /** @returns {number} */
  u8() {
    return this.bytes[this.#advance(1)];
  }

  /** @returns {number} */
  u16() {
    return this.view.getUint16(this.#advance(2), true);
  }

  /** @returns {number} */
  u32() {
    return this.view.getUint32(this.#advance(4), true);
  }

  /** @returns {bigint} a u64, as a BigInt since it may exceed 2^53 */
  u64() {
    return this.view.getBigUint64(this.#advance(8), true);
  }

  /** @returns {number} an f32, widened exactly to a JS number */
  f32() {
    return this.view.getFloat32(this.#advance(4), true);
  }

  /** @returns {number} */
  f64() {
    return this.view.getFloat64(this.#advance(8), true);
  }
}
