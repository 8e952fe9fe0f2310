/**
 * Typed decode errors, one class per variant of the Rust `DecodeError` enum
 * (`proto/src/error.rs`). Every error has `kind` set to the variant name
 * (`'Incomplete'`, `'Malformed'`, `'UnsupportedVersion'`, `'NeedKeyframe'`, `'TooLarge'`)
 * and the variant's fields under the same (camelCased) names.
 * @module
 */

/** Base class of every error the decoder throws for bad input. */
export class DecodeError extends Error {
  /**
   * @param {string} kind variant name, as in the Rust enum
   * @param {string} message human-readable description
   */
  constructor(kind, message) {
    super(message);
    /** @type {string} */
    this.kind = kind;
    this.name = `${kind}Error`;
  }

  /** A plain object (structured-cloneable) with `kind`, `message` and the variant's fields. */
  toJSON() {
    const out = { kind: this.kind, name: this.name, message: this.message };
    for (const k of Object.keys(this)) if (k !== 'kind' && k !== 'name') out[k] = this[k];
    return out;
  }
}

/** The bytes end before the frame does: wait until `needed` bytes in all are available. */
export class IncompleteError extends DecodeError {
  /** @param {number} needed bytes the frame needs @param {number} available bytes given */
  constructor(needed, available) {
    super('Incomplete', `incomplete frame: ${needed} bytes needed, ${available} available`);
    this.needed = needed;
    this.available = available;
  }
}

/** The bytes are not a valid frame; `what` says why. */
export class MalformedError extends DecodeError {
  /** @param {string} what what was wrong */
  constructor(what) {
    super('Malformed', `malformed frame: ${what}`);
    this.what = what;
  }
}

/** The frame uses a format version this decoder does not read. */
export class UnsupportedVersionError extends DecodeError {
  /**
   * @param {number} found version in the frame
   * @param {number} oldest oldest version read here @param {number} newest newest version read here
   */
  constructor(found, oldest, newest) {
    super(
      'UnsupportedVersion',
      `unsupported frame format version ${found} (this decoder reads versions ${oldest} to ${newest})`,
    );
    this.found = found;
    this.oldest = oldest;
    this.newest = newest;
  }
}

/** A delta frame predicts from a frame this decoder does not hold; decode a keyframe first. */
export class NeedKeyframeError extends DecodeError {
  /**
   * @param {bigint} sequence the delta frame's sequence number
   * @param {bigint} base the frame it predicts from
   * @param {bigint|null} held the identity-ordered frame the decoder holds, if any
   */
  constructor(sequence, base, held) {
    super(
      'NeedKeyframe',
      `frame ${sequence} predicts from frame ${base}, but the decoder holds ` +
        `${held === null ? 'None' : `Some(${held})`}: a keyframe is needed`,
    );
    this.sequence = sequence;
    this.base = base;
    this.held = held;
  }
}

/** The frame declares more than the caller's limits allow. */
export class TooLargeError extends DecodeError {
  /**
   * @param {'particles'|'bytes'} what what is too large
   * @param {number} declared declared amount
   * @param {number} limit the caller's limit
   */
  constructor(what, declared, limit) {
    super('TooLarge', `frame declares ${declared} ${what}, over the limit of ${limit}`);
    this.what = what;
    this.declared = declared;
    this.limit = limit;
  }
}
