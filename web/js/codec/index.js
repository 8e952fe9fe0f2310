/**
 * Floe frame codec for the browser viewer: a JavaScript decoder mirroring the Rust reference
 * (`proto/src/decoder.rs`), plain ES modules with no dependencies, usable on a page, in a Web
 * Worker (`worker.js`) and in Node 20.
 *
 * ```js
 * import { Decoder } from './codec/index.js';
 * const decoder = new Decoder({ maxParticles: 1 << 22 });
 * const frame = decoder.decode(arrayBuffer); // frame.header, frame.positions (Float32Array x,y,z), frame.channels
 * ```
 * @module
 */

export { Decoder } from './decoder.js';
export {
  DecodeError, IncompleteError, MalformedError, NeedKeyframeError, TooLargeError, UnsupportedVersionError,
} from './errors.js';
export {
  CHANNELS, ChannelKind, DEFAULT_LIMITS, FIXED_HEADER_LEN, MAGIC, MAX_CHANNELS, MAX_COMPONENTS, MIN_VERSION, Mode,
  VERSION, kindName, readHeader,
} from './header.js';
export { decodeKey, encodeKey } from './morton.js';
export { PREDICTOR_NAMES, Predictor, extrapolate, readCodes } from './predict.js';
export { RangeForm, checkRange, dequantise, maxErrorOf, stepOf } from './quantize.js';
export { Reader } from './reader.js';
export { BLOCK, ESCAPE, Scratch, ZERO_BLOCK, readStream } from './stream.js';
export { readMortonPositions } from './unordered.js';
export { applyResidual, unzigzag, zigzagResidual } from './zigzag.js';
