// Unit tests of the codec's building blocks: the LZ4 block decompressor (bounds above all),
// zigzag residuals, byte planes, Morton keys and f32 formatting. Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import {
  Lz4Error, applyResidual, decodeKey, decompressBlockInto, encodeKey, joinPlanesU16, joinPlanesU48, widthOf,
  zigzagResidual,
} from '../js/codec/index.js';
import { formatF32 } from '../js/codec/quantize.js';

const text = (s) => new TextEncoder().encode(s);
const decode = (block, size) => {
  const out = new Uint8Array(size);
  const n = decompressBlockInto(Uint8Array.from(block), out);
  return new TextDecoder().decode(out.subarray(0, n));
};

test('LZ4 blocks: literals, matches (overlapping too) and extended lengths', () => {
  assert.equal(decode([0x50, ...text('hello')], 5), 'hello');
  assert.equal(decode([0x00], 0), '', 'an empty block is one token with no literals');
  assert.equal(decode([0x14, 97, 1, 0, 0x00], 9), 'a'.repeat(9), 'offset 1 repeats a byte');
  assert.equal(decode([0x24, 97, 98, 2, 0, 0x00], 10), 'ab'.repeat(5), 'offset 2 repeats a pattern');
  assert.equal(decode([0x30, ...text('xyz')], 100), 'xyz', 'fewer bytes than the room is fine here');
  const long = 'q'.repeat(280);
  assert.equal(decode([0xf0, 255, 10, ...text(long)], 280), long, '15 + 255 + 10 literals');
  // 3 literals, then a match of 4 + 15 + 255 + 1 = 275 bytes at offset 3, then an empty literal run.
  assert.equal(decode([0x3f, ...text('abc'), 3, 0, 255, 1, 0x00], 278), 'abc'.repeat(93).slice(0, 278));
  // A long non-overlapping copy.
  const src = 'the quick brown fox jumps over the lazy dog';
  assert.equal(decode([0xff, src.length - 15, ...text(src), src.length, 0, src.length - 19, 0x00], 2 * src.length), src + src);
});

test('LZ4 refuses invalid blocks with lz4_flex error codes', () => {
  const code = (block, size) => {
    try {
      decompressBlockInto(Uint8Array.from(block), new Uint8Array(size));
    } catch (e) {
      assert.ok(e instanceof Lz4Error);
      return e.code;
    }
    return 'ok';
  };
  assert.equal(code([], 10), 'ExpectedAnotherByte');
  assert.equal(code([0x50, 1, 2], 10), 'LiteralOutOfBounds');
  assert.equal(code([0x50, 1, 2, 3, 4, 5], 4), 'OutputTooSmall');
  assert.equal(code([0x10, 97, 0, 0], 10), 'OffsetZero');
  assert.equal(code([0x10, 97, 2, 0, 0x00], 10), 'OffsetOutOfBounds');
  assert.equal(code([0x10, 97, 1], 10), 'ExpectedAnotherByte', 'half an offset');
  assert.equal(code([0x14, 97, 1, 0], 10), 'ExpectedAnotherByte', 'a block ends with a literal run');
  assert.equal(code([0x1f, 97, 1, 0], 100), 'ExpectedAnotherByte', 'match length byte missing');
  assert.equal(code([0x14, 97, 1, 0, 0x00], 8), 'OutputTooSmall');
  assert.equal(code([0xf0, 255], 1000), 'ExpectedAnotherByte', 'literal length bytes missing');
});

test('LZ4 never writes outside its output, whatever the input', () => {
  let s = 7;
  const next = () => { s ^= s << 13; s >>>= 0; s ^= s >>> 17; s ^= s << 5; s >>>= 0; return s; };
  for (let i = 0; i < 20000; i++) {
    const input = new Uint8Array(next() % 64).map(() => next() & 0xff);
    if (i % 2 && input.length) input[0] &= 0x3f; // short runs, so matches are reached more often
    const size = next() % 128;
    const buffer = new Uint8Array(size + 32).fill(0xa5);
    const out = buffer.subarray(16, 16 + size);
    let written = -1;
    try {
      written = decompressBlockInto(input, out);
    } catch (e) {
      assert.ok(e instanceof Lz4Error, String(e));
    }
    assert.ok(written <= size);
    for (let k = 0; k < 16; k++) {
      assert.equal(buffer[k], 0xa5);
      assert.equal(buffer[16 + size + k], 0xa5);
    }
  }
});

test('zigzag residuals invert for every pair of codes (1, 3 and 8 bits) and wrap the short way', () => {
  for (const bits of [1, 3, 8]) {
    const top = (1 << bits) - 1;
    for (let a = 0; a <= top; a++) {
      for (let b = 0; b <= top; b++) {
        const r = zigzagResidual(a, b, bits);
        assert.ok(r <= top);
        assert.equal(applyResidual(r, b, bits), a);
      }
    }
  }
  assert.deepEqual([zigzagResidual(5, 5, 16), zigzagResidual(4, 5, 16), zigzagResidual(6, 5, 16)], [0, 1, 2]);
  assert.equal(zigzagResidual(0, 65535, 16), 2);
  assert.equal(applyResidual(65535, 0, 16), 32768);
});

test('byte planes join little-endian, up to 48 bits', () => {
  const n = 3;
  const planes = Uint8Array.from([1, 2, 3, 0x10, 0x20, 0x30]);
  const out16 = new Uint16Array(n);
  joinPlanesU16(planes, 2, n, out16);
  assert.deepEqual([...out16], [0x1001, 0x2002, 0x3003]);
  const v = [0, 0xffffffffffff, 0x123456789abc];
  const p = new Uint8Array(6 * n);
  v.forEach((x, i) => { for (let k = 0; k < 6; k++) p[k * n + i] = Math.floor(x / 2 ** (8 * k)) & 0xff; });
  const out = new Float64Array(n);
  joinPlanesU48(p, 6, n, out);
  assert.deepEqual([...out], v);
  assert.deepEqual([0, 255, 256, 2 ** 48 - 1].map(widthOf), [1, 1, 2, 6]);
});

test('Morton keys interleave x, y, z and invert', () => {
  assert.deepEqual([encodeKey(1, 0, 0), encodeKey(0, 1, 0), encodeKey(0, 0, 1)], [1, 2, 4]);
  assert.equal(encodeKey(65535, 65535, 65535), 2 ** 48 - 1);
  const q = new Uint16Array(3);
  let s = 99;
  for (let i = 0; i < 10000; i++) {
    s = (Math.imul(s, 1103515245) + 12345) >>> 0;
    const [x, y, z] = [s & 0xffff, s >>> 16, (s >>> 8) & 0xffff ^ i];
    decodeKey(encodeKey(x, y, z), q);
    assert.deepEqual([...q], [x, y, z]);
  }
});

test('f32 values are written as Rust writes them in messages', () => {
  const cases = [[2.05, '2.05'], [1e-7, '0.0000001'], [2 ** 87, '154742510000000000000000000'], [533485184, '533485200'],
    [-0, '-0'], [NaN, 'NaN'], [Infinity, 'inf'], [255, '255'], [-0.0019408078, '-0.0019408078']];
  for (const [v, want] of cases) assert.equal(formatF32(Math.fround(v)), want);
});
