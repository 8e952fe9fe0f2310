// The resolution of moving and still frames (web/js/resolution.js). Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { Resolution } from '../js/resolution.js';

/** Feeds `r` animation frames every `ms` for `seconds`, the picture changing in each. */
function move(r, start, ms, seconds) {
  let t = start, scale = null;
  for (; t < start + 1000 * seconds; t += ms) scale = r.next(t, true);
  return { t, scale };
}

test('slow moving frames are drawn at a lower resolution, down to the least', () => {
  const r = new Resolution({ target: 8, min: 0.5 });
  assert.equal(r.next(0, true), 1);
  // 4 frames a second: under the target, so each second's measurement lowers the resolution.
  const { scale } = move(r, 16, 250, 3);
  assert.ok(scale < 1 && scale > 0.5, `${scale}`);
  const { t, scale: least } = move(r, 4000, 250, 20);
  assert.equal(least, 0.5);
  // Standing still: nothing to draw until the picture has been still for idleMs, then one
  // sharp frame, then nothing.
  assert.equal(r.next(t + 100, false), null);
  assert.equal(r.next(t + 600, false), 1);
  assert.equal(r.next(t + 700, false), null);
  // Moving again: at the moving resolution at once (the sharp frame measured nothing).
  assert.equal(r.next(t + 800, true), 0.5);
});

test('fast frames keep or win back the full resolution', () => {
  const r = new Resolution({ target: 8, min: 0.5 });
  // At 20 frames a second the resolution stays full: no sharp frame is needed after.
  const { t } = move(r, 0, 50, 3);
  assert.equal(r.moving, 1);
  assert.equal(r.next(t + 1000, false), null);
  // Lowered while slow, then fast again: back to full, step by step.
  const slow = move(r, t + 2000, 250, 6);
  assert.ok(r.moving < 0.7);
  move(r, slow.t, 40, 10);
  assert.equal(r.moving, 1);
});

test('frames that come seldom (a scene sending a few frames a second) but draw fast stay sharp', () => {
  const r = new Resolution({ target: 8, min: 0.5 });
  // A frame every 320 ms, drawn in 16 ms, with still animation frames between: full resolution.
  for (let t = 0; t < 10_000; t += 320) {
    assert.equal(r.next(t, true), 1);
    for (let k = 1; k < 20; k++) assert.equal(r.next(t + 16 * k, false), null);
  }
  assert.equal(r.moving, 1);
});

test('a slow frame counts whether or not the next animation frame draws', () => {
  const r = new Resolution({ target: 8, min: 0.5 });
  // Each drawn frame takes 200 ms to come round; the camera moves in every other animation frame.
  let t = 0;
  for (; t < 5000; t += 216) {
    r.next(t, true);
    r.next(t + 200, false);
  }
  assert.ok(r.moving < 0.8, `${r.moving}`);
  // A hidden tab's long pause is no frame's cost.
  const before = r.moving;
  r.next(t, true);
  r.next(t + 60_000, true);
  assert.equal(r.moving, before);
});
