/**
 * LZ4 *block* decompression: the raw block format (no frame, no size prefix) that the Rust
 * encoder writes with `lz4_flex::block::compress_into` and reads with
 * `lz4_flex::block::decompress_into` (`proto/src/stream.rs`). The caller knows the
 * decompressed size and passes an output buffer of exactly that size.
 *
 * Mirrors lz4_flex 0.14's safe decoder (`block/decompress_safe.rs`): a block is a sequence of
 * (token, literals, offset, match) where the last sequence may stop after its literals; the
 * block ends when the input is used up after a literal run. Every read of the input and every
 * write of the output is bounds-checked; an invalid block throws `Lz4Error`.
 * @module
 */

const MINMATCH = 4;

/** Why an LZ4 block could not be decompressed; `code` names the lz4_flex error variant. */
export class Lz4Error extends Error {
  /** @param {string} code lz4_flex `DecompressError` variant @param {string} message */
  constructor(code, message) {
    super(message);
    this.name = 'Lz4Error';
    this.code = code;
  }
}

// Messages as lz4_flex's `Display` writes them.
const expectedAnotherByte = () => new Lz4Error('ExpectedAnotherByte', 'expected another byte, found none');
const outputTooSmall = (expected, actual) =>
  new Lz4Error(
    'OutputTooSmall',
    `provided output is too small for the decompressed data, actual ${actual}, expected ${expected}`,
  );

/**
 * Decompresses the LZ4 block `input` into `output` (at most `output.length` bytes).
 * @param {Uint8Array} input the compressed block
 * @param {Uint8Array} output where the bytes go; its length is the most that may be written
 * @returns {number} bytes written (the caller checks that this is the size it expected)
 * @throws {Lz4Error} on a truncated block, a zero or out-of-range match offset, or output overflow
 */
export function decompressBlockInto(input, output) {
  const inLen = input.length;
  const cap = output.length;
  let ip = 0;
  let op = 0;
  for (;;) {
    if (ip >= inLen) throw expectedAnotherByte();
    const token = input[ip++];

    // Literals.
    let lit = token >>> 4;
    if (lit !== 0) {
      if (lit === 15) {
        let extra;
        do {
          if (ip >= inLen) throw expectedAnotherByte();
          extra = input[ip++];
          lit += extra;
        } while (extra === 255);
      }
      if (lit > inLen - ip) {
        throw new Lz4Error('LiteralOutOfBounds', 'literal is out of bounds of the input');
      }
      if (lit > cap - op) {
        throw outputTooSmall(op + lit, cap);
      }
      if (lit < 32) {
        for (let i = 0; i < lit; i++) output[op + i] = input[ip + i];
      } else {
        output.set(input.subarray(ip, ip + lit), op);
      }
      ip += lit;
      op += lit;
    }

    // The block ends after a literal run that uses up the input.
    if (ip >= inLen) break;

    // Match.
    if (inLen - ip < 2) throw expectedAnotherByte();
    const offset = input[ip] | (input[ip + 1] << 8);
    ip += 2;
    if (offset === 0) throw new Lz4Error('OffsetZero', '0 is not a valid match offset');
    let len = MINMATCH + (token & 15);
    if (len === MINMATCH + 15) {
      let extra;
      do {
        if (ip >= inLen) throw expectedAnotherByte();
        extra = input[ip++];
        len += extra;
      } while (extra === 255);
    }
    if (len > cap - op) {
      throw outputTooSmall(op + len, cap);
    }
    if (offset > op) {
      throw new Lz4Error('OffsetOutOfBounds', 'the offset to copy is not contained in the decompressed buffer');
    }
    const from = op - offset;
    if (offset === 1) {
      output.fill(output[from], op, op + len);
    } else if (len > offset || len < 32) {
      // Overlapping (or short) copy: byte by byte, so a run repeats its pattern.
      for (let i = 0; i < len; i++) output[op + i] = output[from + i];
    } else {
      output.copyWithin(op, from, from + len);
    }
    op += len;
  }
  return op;
}
