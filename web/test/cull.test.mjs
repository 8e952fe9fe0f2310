// Fewer particles where the fluid hides them (web/js/cull.js). Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { CELL, cubeLumps, cubesOf, innerCubes, lumpedParticles, outerParticles } from '../js/cull.js';

/** A lattice block of side^3 particles `h` apart from `origin`, with a value per particle. */
function block(side, h, origin = [0, 0, 0]) {
  const positions = new Float32Array(3 * side ** 3), values = new Float32Array(side ** 3);
  let i = 0;
  for (let x = 0; x < side; x++) for (let y = 0; y < side; y++) for (let z = 0; z < side; z++) {
    positions.set([origin[0] + (x + 0.5) * h, origin[1] + (y + 0.5) * h, origin[2] + (z + 0.5) * h], 3 * i);
    values[i] = i++;
  }
  return { positions, values };
}

const boxOf = (p) => {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < p.length; i++) { min[i % 3] = Math.min(min[i % 3], p[i]); max[i % 3] = Math.max(max[i % 3], p[i]); }
  return { min, max };
};

test('a block keeps every particle within four spacings of its faces and drops most inside', () => {
  const h = 0.01, side = 30, { positions, values } = block(side, h);
  const cubes = innerCubes(positions, h, boxOf(positions));
  const out = outerParticles(positions, values, cubes);
  const n = side ** 3;
  assert.equal(out.positions.length / 3 + cubes.hidden, n);
  assert.equal(out.values.length, out.positions.length / 3);
  assert.ok(cubes.hidden > 0.3 * n, `only ${cubes.hidden} of ${n} left out`);
  const kept = new Set(Array.from(out.values));
  for (let i = 0; i < n; i++) {
    const p = positions.subarray(3 * i, 3 * i + 3);
    const depth = Math.min(...[0, 1, 2].map((k) => Math.min(p[k], side * h - p[k])));
    if (depth < 4 * h) assert.ok(kept.has(i), `particle ${i}, ${(depth / h).toFixed(1)} spacings deep, was left out`);
    else if (kept.has(i)) assert.ok(depth < 8 * h, `particle ${i}, ${(depth / h).toFixed(1)} spacings deep, was kept`);
  }
  // Values stay with their particles, in order.
  const j = out.values.indexOf(100);
  assert.deepEqual(Array.from(out.positions.subarray(3 * j, 3 * j + 3)), Array.from(positions.subarray(300, 303)));
});

test('thin or sparse particles are all kept', () => {
  const h = 0.01;
  // A sheet 4 spacings thick: nothing is four spacings deep.
  const sheet = block(40, h);
  const thin = sheet.positions.filter((_, i) => i % 3 !== 1 || sheet.positions[i] < 4 * h);
  const t = new Float32Array(thin.length);
  let k = 0;
  for (let i = 0; i < sheet.positions.length; i += 3) {
    if (sheet.positions[i + 1] < 4 * h) { t.set(sheet.positions.subarray(i, i + 3), k); k += 3; }
  }
  const tp = t.subarray(0, k);
  assert.equal(innerCubes(tp, h, boxOf(tp)), null);
  // Particles eight spacings apart: no cube is full.
  const sparse = block(20, 8 * h);
  assert.equal(innerCubes(sparse.positions, h, boxOf(sparse.positions)), null);
  // No spacing known, or no particles: nothing left out.
  assert.equal(innerCubes(sparse.positions, 0, boxOf(sparse.positions)), null);
  assert.equal(innerCubes(new Float32Array(0), h, { min: [0, 0, 0], max: [0, 0, 0] }), null);
  const all = outerParticles(sparse.positions, sparse.values, null);
  assert.equal(all.positions, sparse.positions);
  assert.deepEqual(Array.from(lumpedParticles(sparse.positions, null).scales), new Array(8000).fill(1));
});

test('the surface view gets one sphere per inner cube, of its particles\' volume, at their centre', () => {
  const h = 0.01, side = 24, { positions } = block(side, h);
  const cubes = innerCubes(positions, h, boxOf(positions));
  const lumped = lumpedParticles(positions, cubes);
  const outer = side ** 3 - cubes.hidden, lumps = lumped.scales.length - outer;
  assert.ok(lumps > 0);
  assert.deepEqual(Array.from(lumped.positions.subarray(0, 3 * outer)), Array.from(outerParticles(positions, null, cubes).positions));
  assert.ok(lumped.scales.subarray(0, outer).every((s) => s === 1));
  // Volume kept: the scales cubed add up to the particles merged (8 a cube in a lattice).
  const volume = lumped.scales.subarray(outer).reduce((a, s) => a + s ** 3, 0);
  assert.ok(Math.abs(volume - cubes.hidden) < 1e-3 * cubes.hidden, `${volume} for ${cubes.hidden} particles`);
  assert.equal(lumps, cubes.hidden / 8);
  // A lump sits at its cube's centre, between lattice points.
  const [x, y, z] = lumped.positions.subarray(3 * outer, 3 * outer + 3);
  for (const v of [x, y, z]) assert.ok(Math.abs(v / h - Math.round(v / h)) < 1e-4, `${v / h} is not on a lattice corner`);
});

test('seen from afar, every cube is one sphere of its particles\' volume at their centre', () => {
  const h = 0.01, side = 9, { positions } = block(side, h);
  const grid = cubesOf(positions, h, boxOf(positions));
  const far = cubeLumps(positions, grid);
  // 9 particles a side: four full cubes of 2 and a last layer of 1 along each axis.
  assert.equal(far.scales.length, 5 ** 3);
  const volume = far.scales.reduce((a, s) => a + s ** 3, 0);
  assert.ok(Math.abs(volume - side ** 3) < 1e-3 * side ** 3, `${volume} for ${side ** 3} particles`);
  assert.equal(Math.max(...far.scales).toFixed(4), CELL.toFixed(4));
  assert.equal(Math.min(...far.scales), 1);
  // The first lump holds the first 2 x 2 x 2 particles: its centre is their mean.
  assert.deepEqual(Array.from(far.positions.subarray(0, 3), (v) => Number((v / h).toFixed(4))), [1, 1, 1]);
  // Without a spacing there is no grid: the particles themselves.
  const none = cubeLumps(positions, cubesOf(positions, 0, boxOf(positions)));
  assert.equal(none.positions, positions);
  assert.ok(none.scales.every((s) => s === 1));
  // The grid the inner cubes are found on is the same one.
  assert.deepEqual(innerCubes(positions, h, boxOf(positions), grid), innerCubes(positions, h, boxOf(positions)));
});
