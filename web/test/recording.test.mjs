// Recordings (web/js/recording.js) and seeking in them (web/js/player.js), on a recording made
// by `floectl record` (512 particles of a dam break, 40 identity-ordered frames, keyframes at 0
// and 30) whose positions the Rust decoder exported (data/dam_break_512.expected.json). Made with
//   floectl create dam_break --set particle_spacing=0.0625 && floectl run 1 --rtf 0
//   floectl record 1 --out dam_break_512.rec --frames 40 --fps 30
//   floectl export --recording dam_break_512.rec --out frames --format csv   (particles 0, 1, 255, 511 kept)
// and made anew when the frame format's version changes. Run: node --test web/test/
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import { Decoder } from '../js/codec/index.js';
import { Player, advance, naturalSpeed } from '../js/player.js';
import { RecordingError, RecordingWriter, frameSpans } from '../js/recording.js';

const DATA = new URL('./data/', import.meta.url);
const recording = new Uint8Array(readFileSync(new URL('dam_break_512.rec', DATA)));
const expected = JSON.parse(readFileSync(new URL('dam_break_512.expected.json', DATA), 'utf8'));
const golden = (name) => new Uint8Array(readFileSync(new URL(`../../proto/testdata/${name}.bin`, import.meta.url)));

test('a floectl recording splits into its frames', () => {
  const spans = frameSpans(recording);
  assert.equal(spans.length, expected.frames);
  assert.equal(spans[0].offset, 12);
  const last = spans.at(-1);
  assert.equal(last.offset + last.length, recording.length);
});

test('the player decodes every frame as the Rust decoder did, in any order', () => {
  const player = new Player(recording, { checkpointEvery: 8 });
  assert.equal(player.length, 40);
  assert.deepEqual(player.headers.flatMap((h, i) => (h.keyframe ? [i] : [])), expected.keyframes);
  player.prepare();
  for (const k of [39, 0, 31, 29, 30, 1, 17, 16, 15, 38, 2]) {
    const frame = player.frame(k);
    assert.equal(frame.header.sequence, player.headers[k].sequence);
    for (const [id, ...xyz] of expected.particles[k] ?? []) {
      for (let c = 0; c < 3; c++) {
        assert.equal(frame.positions[3 * id + c], Math.fround(xyz[c]), `frame ${k}, particle ${id}, axis ${c}`);
      }
    }
  }
});

test('seeking gives the frames a decoder reading the whole stream gives', () => {
  const decoder = new Decoder();
  const spans = frameSpans(recording);
  const inOrder = spans.map((s) => decoder.decode(recording.subarray(s.offset, s.offset + s.length)).positions);
  // Without prepare(): states are kept as seeks pass them.
  const player = new Player(recording, { checkpointEvery: 4 });
  const order = [25, 26, 24, 9, 8, 39, 3, 4, 5, 30, 29, 12, 13, 0, 37, 36, 20];
  for (const k of order) assert.deepEqual(player.frame(k).positions, inOrder[k], `frame ${k}`);
  // Kept states: delta frames at multiples of 4 that a seek passed.
  for (const k of player.states.keys()) assert.equal(k % 4, 0);
  assert.ok(player.states.size > 0);
  player.prepare();
  for (let k = 0; k < 3; k++) {
    const all = inOrder.flatMap((p) => Array.from(p.filter((_, i) => i % 3 === k)));
    assert.equal(player.extent.min[k], Math.min(...all));
    assert.equal(player.extent.max[k], Math.max(...all));
  }
  assert.equal(player.states.size, [...Array(40).keys()].filter((k) => k % 4 === 0 && !expected.keyframes.includes(k)).length);
  for (let k = 39; k >= 0; k--) assert.deepEqual(player.frame(k).positions, inOrder[k], `frame ${k}`);
});

test('a recording written here reads back, from its first keyframe on', async () => {
  const writer = new RecordingWriter();
  assert.equal(writer.push(golden('identity_delta')), false, 'a delta frame cannot start a recording');
  assert.equal(writer.push(golden('identity_keyframe')), true);
  assert.equal(writer.push(golden('identity_delta')), true);
  assert.equal(writer.push(golden('identity_linear')), true);
  assert.equal(writer.frames, 3);
  const bytes = new Uint8Array(await writer.blob().arrayBuffer());
  assert.equal(bytes.length, writer.bytes);
  assert.equal(new TextDecoder().decode(bytes.subarray(0, 8)), 'FLOEREC1');
  const player = new Player(bytes);
  const decoder = new Decoder();
  for (const [k, name] of ['identity_keyframe', 'identity_delta', 'identity_linear'].entries()) {
    assert.deepEqual(player.frame(k).positions, decoder.decode(golden(name)).positions, name);
  }
  const small = new RecordingWriter(8 + 4 + golden('unordered_positions').length);
  assert.equal(small.push(golden('unordered_positions')), true);
  assert.equal(small.push(golden('unordered_positions')), false, 'a full recording takes no more frames');
});

test('a file that is not a whole recording is refused, naming what is wrong', () => {
  const refuse = (bytes, pattern) => assert.throws(() => new Player(bytes), (e) => e instanceof RecordingError && pattern.test(e.message));
  refuse(new TextEncoder().encode('FLOEREC2'), /not a Floe recording/);
  refuse(new Uint8Array(3), /not a Floe recording/);
  refuse(recording.subarray(0, 8), /holds no frames/);
  refuse(recording.subarray(0, recording.length - 10), /frame 39 declares \d+ bytes, but the file ends after \d+/);
  refuse(recording.subarray(0, 10), /frame 0: the file ends inside its length/);
  const spans = frameSpans(recording);
  // Frames 1 on alone: a delta frame first.
  const tail = new Uint8Array(8 + recording.length - (spans[1].offset - 4));
  tail.set(recording.subarray(0, 8));
  tail.set(recording.subarray(spans[1].offset - 4), 8);
  refuse(tail, /frame 0 is a delta frame/);
  // A damaged magic in frame 2's header.
  const bad = recording.slice();
  bad[spans[2].offset] = 0;
  refuse(bad, /frame 2: malformed frame: not a Floe frame/);
  assert.throws(() => new Player(recording).frame(40), RangeError);
});

test('playback moves through frames by simulated time', () => {
  const times = [0, 0.1, 0.2, 0.2, 0.05, 0.15];
  assert.deepEqual(advance(times, 0, 0.05), { index: 0, elapsed: 0.05 });
  assert.deepEqual(advance(times, 0, 0.1), { index: 1, elapsed: 0 });
  // A repeated time and a step back (a reset while recording) take no time.
  const r = advance(times, 1, 0.15);
  assert.equal(r.index, 4);
  assert.ok(Math.abs(r.elapsed - 0.05) < 1e-12);
  assert.deepEqual(advance(times, 4, 10), { index: 5, elapsed: 0 });
});

test('a replay starts at the speed that shows about 30 frames a second, at most real time', () => {
  const speeds = [0.01, 0.1, 0.5, 1, 2];
  // 101 frames 1 ms apart: 0.03 simulated seconds per wall second; the nearest offered below.
  assert.equal(naturalSpeed(Array.from({ length: 101 }, (_, i) => i * 1e-3), speeds), 0.01);
  assert.equal(naturalSpeed([0, 0.02, 0.04], speeds), 0.5);
  assert.equal(naturalSpeed([0, 1, 2], speeds), 1, 'never faster than real time');
  assert.equal(naturalSpeed([0, 1e-7], speeds), 0.01, 'the slowest when none is slow enough');
  assert.equal(naturalSpeed([0.5], speeds), 1);
  assert.equal(naturalSpeed(new Player(recording).times, speeds), 0.5, 'the floectl recording: frames 20 ms apart');
});
