// The terrain mesh (web/js/terrain.js). Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { terrainMesh } from '../js/terrain.js';

test('a terrain grid becomes two triangles per cell at its nodes', () => {
  // 3 x 2 nodes over x in [1, 3], z in [2, 3]: a plane rising 0.5 m per metre along x.
  const t = { min: [1, 2], max: [3, 3], nx: 3, nz: 2, heights: [0, 0.5, 1, 0, 0.5, 1] };
  const { positions, normals, indices } = terrainMesh(t);
  assert.equal(positions.length, 6 * 3);
  assert.deepEqual([...positions.slice(0, 3)], [1, 0, 2]);
  assert.deepEqual([...positions.slice(15, 18)], [3, 1, 3]);
  assert.equal(indices.length, 2 * 2 * 3);
  assert.ok([...indices].every((i) => i < 6));
  // Every node's normal is the plane's: (-0.5, 1, 0) normalised.
  const len = Math.hypot(0.5, 1);
  for (let v = 0; v < 6; v++) {
    const n = [...normals.slice(v * 3, v * 3 + 3)];
    [-0.5 / len, 1 / len, 0].forEach((w, k) => assert.ok(Math.abs(n[k] - w) < 1e-6, `node ${v}: ${n}`));
  }
  // Triangles face up (counter-clockwise seen from above: +y cross product).
  for (let f = 0; f < indices.length; f += 3) {
    const [a, b, c] = [0, 1, 2].map((j) => [...positions.slice(indices[f + j] * 3, indices[f + j] * 3 + 3)]);
    const u = b.map((x, k) => x - a[k]), w = c.map((x, k) => x - a[k]);
    assert.ok(u[2] * w[0] - u[0] * w[2] > 0, `triangle ${f / 3} faces down`);
  }
});
