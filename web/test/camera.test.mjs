// Camera framing (web/js/camera.js) and the floor's cell size (web/js/floor.js).
// Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { FOVY, framingDistance, lookAt, orbitDirection, perspective } from '../js/camera.js';
import { cellSize } from '../js/floor.js';

/** Normalised device coordinates of `p` through column-major `proj * view`. */
function project(proj, view, p) {
  const mul = (m, v) => [0, 1, 2, 3].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3]);
  const c = mul(proj, mul(view, [...p, 1]));
  return [c[0] / c[3], c[1] / c[3]];
}

test('a framed box shows whole, as near as the margin allows', () => {
  const boxes = [
    [[0, 0, 0], [1.6, 0.8, 0.2]], // a long, thin tank
    [[-1, -1, -1], [1, 1, 1]],
    [[0, 0, 0], [0.2, 2, 0.2]], // a tall column
  ];
  for (const [min, max] of boxes) {
    for (const aspect of [0.5, 1, 1.8]) {
      for (const [yaw, pitch] of [[0.5, 0.4], [0, 0], [2, -0.3]]) {
        const margin = 1.08;
        const d = framingDistance(min, max, yaw, pitch, FOVY, aspect, margin);
        const target = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
        const eye = orbitDirection(yaw, pitch).map((v, k) => target[k] + d * v);
        const view = lookAt(eye, target), proj = perspective(FOVY, aspect, 0.01, 100);
        let widest = 0;
        for (let i = 0; i < 8; i++) {
          const corner = [0, 1, 2].map((k) => ((i >> k) & 1 ? max[k] : min[k]));
          const [x, y] = project(proj, view, corner);
          const extent = Math.max(Math.abs(x), Math.abs(y));
          assert.ok(extent <= 1 / margin + 1e-6, `corner ${corner} at ${x}, ${y} (aspect ${aspect})`);
          widest = Math.max(widest, extent);
        }
        assert.ok(widest > 1 / margin - 1e-6, `not framed tightly: the widest corner at ${widest}`);
      }
    }
  }
});

test('a shifted projection moves the centre of the view', () => {
  const view = lookAt([0, 0, 3], [0, 0, 0]);
  const [x] = project(perspective(FOVY, 1.5, 0.01, 100, 0.25), view, [0, 0, 0]);
  assert.ok(Math.abs(x - 0.25) < 1e-12);
});

test('floor cells are round numbers, about a tenth of the floor', () => {
  assert.equal(cellSize(1.6), 0.2);
  assert.equal(cellSize(2), 0.2);
  assert.equal(cellSize(0.7), 0.1);
  assert.equal(cellSize(30), 5);
});
