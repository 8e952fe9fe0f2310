// What the surface view works out on the CPU (web/js/surface.js). Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { pixelsAcross } from '../js/surface.js';

/** Column-major perspective projection with focal length `f` (aspect 1), and the identity view. */
const f = 2;
const proj = new Float32Array([f, 0, 0, 0, 0, f, 0, 0, 0, 0, -1.002, -1, 0, 0, -0.2002, 0]);
const view = new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);

test('a length spans its pixels where the box comes nearest the eye', () => {
  // The box reaches from 4 m to 2 m in front of the eye: a spacing of 1 cm spans f h l / (2 z)
  // = 2 * 400 * 0.01 / 4 = 2 pixels at 2 m.
  const box = { min: [-0.5, -0.5, -4], max: [0.5, 0.5, -2] };
  assert.ok(Math.abs(pixelsAcross(0.01, box, proj, view, 400) - 2) < 1e-9);
  // Twice as far: half as many.
  const far = { min: [-0.5, -0.5, -8], max: [0.5, 0.5, -4] };
  assert.ok(Math.abs(pixelsAcross(0.01, far, proj, view, 400) - 1) < 1e-9);
  // The eye inside the box, or the box behind it: no bound on the size.
  assert.equal(pixelsAcross(0.01, { min: [-1, -1, -1], max: [1, 1, 1] }, proj, view, 400), Infinity);
  assert.equal(pixelsAcross(0.01, { min: [-1, -1, 1], max: [1, 1, 2] }, proj, view, 400), Infinity);
});
