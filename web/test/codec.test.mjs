// Golden frames and robustness of the JavaScript frame decoder (web/js/codec/), mirroring
// proto/tests/golden.rs and proto/tests/robustness.rs. Run: node --test web/test/
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import {
  CHANNELS, DecodeError, Decoder, FIXED_HEADER_LEN, IncompleteError, MalformedError, NeedKeyframeError, TooLargeError,
  extrapolate, readHeader,
} from '../js/codec/index.js';

const DATA = new URL('../../proto/testdata/', import.meta.url);
const CURRENT = [
  'unordered_positions', 'unordered_channels', 'identity_keyframe', 'identity_delta', 'identity_linear', 'grid_field',
  'identity_ids', 'identity_ids_delta',
];
// Format version 3 and 4 frames, decoded to show old recordings still read.
const V3 = ['unordered_positions', 'unordered_channels', 'identity_keyframe', 'identity_delta', 'identity_linear'].map((n) => `v3/${n}`);
const V4 = [
  'unordered_positions', 'unordered_channels', 'identity_keyframe', 'identity_delta', 'identity_linear', 'grid_field',
].map((n) => `v4/${n}`);
const NAMES = [...CURRENT, ...V4, ...V3];
const bin = (name) => new Uint8Array(readFileSync(new URL(`${name}.bin`, DATA)));
// u64 fields as strings before parsing, so values past 2^53 would compare exactly too.
const sidecarText = (name) =>
  JSON.parse(
    readFileSync(new URL(`${name}.json`, DATA), 'utf8').replace(
      /"(scene_id|sequence|base_sequence|step)": (\d+)/g, '"$1": "$2"'),
  );
const SIDECARS = new Map(NAMES.map((n) => [n, sidecarText(n)]));
const sidecar = (name) => structuredClone(SIDECARS.get(name));
const BINS = new Map(NAMES.map((n) => [n, bin(n)]));
const put32 = (b, at, v) => new DataView(b.buffer, b.byteOffset).setUint32(at, v, true);

/** A decoder holding what `name` predicts from (the sidecar's `decode_after`, in order). */
function primed(name, limits) {
  const d = new Decoder(limits);
  const dir = name.includes('/') ? `${name.slice(0, name.lastIndexOf('/') + 1)}` : '';
  for (const before of SIDECARS.get(name).decode_after) d.decode(BINS.get(dir + before.replace(/\.bin$/, '')));
  return d;
}

/** The decoded frame in the sidecar's shape (snake_case, vectors as [x, y, z]). */
function sidecarShape(frame) {
  const h = frame.header;
  const out = {
    header: {
      version: h.version, mode: h.mode, keyframe: h.keyframe, frame_len: h.frameLen,
      particle_count: h.particleCount, scene_id: h.sceneId, set: h.set, sequence: h.sequence,
      base_sequence: h.baseSequence, step: h.step, time: h.time,
      channels: h.channels.map((c) => ({
        kind: c.kind, tag: c.tag, components: c.components, bits: c.bits, predictor: c.predictor,
        predictor_tag: c.predictorTag, payload_len: c.payloadLen,
        ranges: c.ranges.map((r) => ({ min: r.min, max: r.max, max_error: r.maxError })),
      })),
    },
  };
  const perParticle = (v, c) => (c === 1 ? Array.from(v) : Array.from({ length: v.length / c }, (_, i) => Array.from(v.subarray(c * i, c * i + c))));
  out.positions = perParticle(frame.positions, 3);
  out.channels = Object.fromEntries(frame.channels.map((ch) => [ch.name, perParticle(ch.values, ch.components)]));
  if (frame.grid) out.grid = frame.grid;
  if (frame.ids) out.ids = Array.from(frame.ids);
  return out;
}

/** Where `got` and `want` first differ (numbers compared with Object.is: bit for bit), or null. */
function firstDifference(path, got, want) {
  if (typeof got === 'bigint') {
    const same = typeof want === 'bigint' ? got === want : typeof want === 'string' && BigInt(want) === got;
    return same ? null : `${path}: ${got} vs ${want}`;
  }
  if (Array.isArray(want)) {
    if (!Array.isArray(got) || got.length !== want.length) return `${path}: length ${got?.length} vs ${want.length}`;
    for (let i = 0; i < want.length; i++) {
      const d = firstDifference(`${path}[${i}]`, got[i], want[i]);
      if (d) return d;
    }
    return null;
  }
  if (want !== null && typeof want === 'object') {
    if (got === null || typeof got !== 'object') return `${path}: ${got} vs an object`;
    for (const k of new Set([...Object.keys(got), ...Object.keys(want)])) {
      const d = firstDifference(`${path}.${k}`, got[k], want[k]);
      if (d) return d;
    }
    return null;
  }
  return Object.is(got, want) ? null : `${path}: decoded ${got}, sidecar ${want}`;
}

for (const name of NAMES) {
  test(`golden ${name} decodes to its sidecar exactly`, () => {
    const bytes = bin(name);
    const want = sidecar(name);
    const frame = primed(name).decode(bytes);
    assert.equal(frame.header.magic, 'FLOF');
    assert.equal(frame.header.frameLen, bytes.length);
    assert.ok(frame.positions instanceof Float32Array);
    for (const ch of frame.channels) assert.ok(ch.values instanceof (ch.name === 'material' ? Uint8Array : Float32Array));
    delete want.description;
    delete want.decode_after;
    assert.equal(firstDifference(name, sidecarShape(frame), want), null);
  });
}

test('golden frames decode from an ArrayBuffer and from an offset view with bytes after the frame', () => {
  for (const name of NAMES) {
    const bytes = bin(name);
    const a = primed(name).decode(bytes.slice().buffer);
    const padded = new Uint8Array(bytes.length + 13).fill(0xab);
    padded.set(bytes, 5);
    const b = primed(name).decode(padded.subarray(5));
    assert.equal(firstDifference(name, sidecarShape(b), sidecarShape(a)), null);
  }
});

test('one decoder follows the identity stream, and keeps its state when a frame is refused', () => {
  const d = new Decoder();
  assert.equal(d.heldSequence, null);
  d.decode(bin('identity_keyframe'));
  const good = bin('identity_delta');
  const h = readHeader(good);
  // Damage the stream width of the last channel (material): the refusal comes after positions
  // and velocities have been decoded.
  const last = good.slice();
  last[h.frameLen - h.channels.at(-1).payloadLen] = 9;
  assert.throws(() => d.decode(last), (e) => e instanceof MalformedError &&
    /channel 2 \(material\): stream width 9 bits \(at most 8 allowed\)/.test(e.what));
  assert.equal(d.heldSequence, 0n);
  assert.equal(d.lastSequence, 0n);
  const delta = d.decode(good);
  assert.equal(firstDifference('delta', sidecarShape(delta).positions, sidecar('identity_delta').positions), null);
  assert.equal(d.heldSequence, 1n);
  const linear = d.decode(bin('identity_linear'));
  assert.equal(firstDifference('linear', sidecarShape(linear).positions, sidecar('identity_linear').positions), null);
  assert.equal(d.lastSequence, 2n);
  // An unordered frame does not disturb the held identity frame.
  d.decode(bin('unordered_positions'));
  assert.equal(d.heldSequence, 2n);
  d.reset();
  assert.deepEqual([d.heldSequence, d.lastSequence], [null, null]);
});

test('a channel whose tag the table lacks decodes as floats under its tag', () => {
  const frame = new Decoder().decode(bin('unordered_channels'));
  const extra = frame.channels.find((ch) => ch.tag === 64);
  assert.deepEqual([extra.name, extra.components, extra.values.length], ['channel 64', 2, 600]);
  assert.ok(extra.values instanceof Float32Array);
  assert.deepEqual(frame.header.channels.map((c) => c.kind),
    ['position', 'velocity', 'density', 'pressure', 'temperature', 'material', 'channel 64']);
  assert.equal(frame.header.set, 1);
  const grid = new Decoder().decode(bin('grid_field'));
  assert.deepEqual([grid.header.mode, grid.header.set, grid.grid.dims, grid.positions.length], ['grid', 2, [8, 1, 6], 0]);
});

test('the channel table is a byte-for-byte copy of proto/channels.json', () => {
  const json = readFileSync(new URL('../../proto/channels.json', import.meta.url), 'utf8');
  const copy = readFileSync(new URL('../js/codec/channels.js', import.meta.url), 'utf8');
  const start = copy.indexOf('export const TABLE =\n') + 'export const TABLE =\n'.length;
  assert.equal(copy.slice(start, copy.lastIndexOf(';')), json);
  assert.deepEqual(CHANNELS.map((c) => c.name), JSON.parse(json).channels.map((c) => c.name));
});

test('every truncated prefix of every golden frame is Incomplete', () => {
  for (const name of NAMES) {
    const bytes = bin(name);
    const d = primed(name);
    for (let len = 0; len < bytes.length; len++) {
      assert.throws(() => d.decode(bytes.subarray(0, len)), (e) => {
        assert.ok(e instanceof IncompleteError, `${name}: prefix ${len} gave ${e}`);
        assert.equal(e.kind, 'Incomplete');
        assert.equal(e.available, len);
        assert.ok(e.needed > len && e.needed <= bytes.length, `${name}: prefix ${len} needs ${e.needed}`);
        return true;
      });
    }
    const h = readHeader(bytes);
    assert.equal(d.decode(bytes).positions.length, h.mode === 'grid' ? 0 : 3 * h.particleCount);
  }
});

/** xorshift32: deterministic noise for the tests. */
function rng(seed) {
  let s = seed >>> 0 || 1;
  return () => {
    s ^= s << 13; s >>>= 0; s ^= s >>> 17; s ^= s << 5; s >>>= 0;
    return s;
  };
}

test('20,000 random buffers are refused with a typed error', () => {
  const next = rng(12);
  const real = bin('unordered_channels');
  const d = new Decoder();
  const kinds = new Map();
  for (let i = 0; i < 20000; i++) {
    const len = next() % 601;
    const bytes = new Uint8Array(len).map(() => next() & 0xff);
    if (i % 2 === 1) {
      // A genuine fixed header, so the table and payload parsers see the noise.
      bytes.set(real.subarray(0, Math.min(FIXED_HEADER_LEN, len)));
      if (len >= 12) new DataView(bytes.buffer).setUint32(8, len, true);
    }
    assert.throws(() => d.decode(bytes), (e) => {
      assert.ok(e instanceof DecodeError, `${len} random bytes gave ${e}`);
      kinds.set(e.kind, (kinds.get(e.kind) ?? 0) + 1);
      return true;
    });
  }
  assert.ok(kinds.get('Malformed') > 0);
});

test('a delta frame without its keyframe throws NeedKeyframe', () => {
  assert.throws(() => new Decoder().decode(bin('identity_delta')), (e) => {
    assert.ok(e instanceof NeedKeyframeError);
    assert.equal(e.kind, 'NeedKeyframe');
    assert.deepEqual([e.sequence, e.base, e.held], [1n, 0n, null]);
    return true;
  });
  const d = new Decoder();
  d.decode(bin('identity_keyframe'));
  assert.throws(() => d.decode(bin('identity_linear')), (e) =>
    e instanceof NeedKeyframeError && e.sequence === 2n && e.base === 1n && e.held === 0n);
  d.reset();
  assert.throws(() => d.decode(bin('identity_delta')), NeedKeyframeError);
});

test('limits: TooLarge before anything is allocated', () => {
  const b = bin('unordered_channels');
  assert.throws(() => new Decoder({ maxParticles: 299 }).decode(b), (e) => {
    assert.ok(e instanceof TooLargeError);
    assert.deepEqual([e.kind, e.what, e.declared, e.limit], ['TooLarge', 'particles', 300, 299]);
    return true;
  });
  assert.equal(new Decoder({ maxParticles: 300 }).decode(b).positions.length, 900);
  assert.throws(() => new Decoder({ maxFrameBytes: 100 }).decode(b.subarray(0, FIXED_HEADER_LEN)), (e) =>
    e instanceof TooLargeError && e.what === 'bytes' && e.limit === 100);
  // A small frame claiming 16 Mi particles is refused by the plane-length check.
  put32(b, 12, 1 << 24);
  assert.throws(() => new Decoder().decode(b), MalformedError);
});

test('the linear extrapolation rounds halves up and wraps, as in proto/src/predict.rs', () => {
  const ONE = 4096;
  // (base, before, gain, prediction): the table of the Rust unit test.
  const cases = [
    [100, 90, ONE, 110], [100, 90, -ONE, 90], [100, 90, (3 * ONE) / 2, 115], [100, 99, ONE / 2, 101],
    [100, 101, ONE / 2, 100], [100, 101, -ONE / 2, 101], [65535, 0, ONE, 65534], [50000, 10000, ONE, 24464],
    [3, 60000, -32768, 21227],
  ];
  for (const [base, before, gain, want] of cases) {
    assert.equal(extrapolate(base, before, gain), want, `extrapolate(${base}, ${before}, ${gain})`);
  }
});

test('non-byte input is a TypeError, not a decode error', () => {
  assert.throws(() => new Decoder().decode('FLOF'), TypeError);
});
