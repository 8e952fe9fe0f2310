// The other sets' drawing (others.js): a grid's tiles sit on its cells, coloured by value.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { gridTiles, ramp } from '../js/others.js';

test('a flat grid is one tile per cell at its floor, coloured by value', () => {
  const grid = { origin: [0, 1, 0], size: [2, 5, 4], dims: [2, 1, 2] };
  const { positions, colours, count } = gridTiles(grid, Float32Array.from([0, 1, 2, 3]));
  assert.equal(count, 24);
  // Every vertex at the grid's floor, y = 1.
  for (let v = 0; v < count; v++) assert.equal(positions[3 * v + 1], 1);
  // Cell 3 (i = 1, k = 1): centred at (1.5, 3), 0.9 of its 1 x 2 cell.
  const xs = [], zs = [];
  for (let v = 18; v < 24; v++) { xs.push(positions[3 * v]); zs.push(positions[3 * v + 2]); }
  assert.deepEqual([Math.min(...xs), Math.max(...xs)].map((x) => +x.toFixed(4)), [1.05, 1.95]);
  assert.deepEqual([Math.min(...zs), Math.max(...zs)].map((z) => +z.toFixed(4)), [2.1, 3.9]);
  // The smallest value takes the map's first colour, the largest its last.
  assert.deepEqual([...colours.slice(0, 3)].map((c) => +c.toFixed(3)), ramp(0).map((c) => +c.toFixed(3)));
  assert.deepEqual([...colours.slice(54, 57)].map((c) => +c.toFixed(3)), ramp(1).map((c) => +c.toFixed(3)));
});

test('a deeper grid draws each layer at its cells\' centre height', () => {
  const grid = { origin: [0, 0, 0], size: [1, 2, 1], dims: [1, 2, 1] };
  const { positions } = gridTiles(grid, null);
  assert.equal(positions[1], 0.5);
  assert.equal(positions[18 + 1], 1.5);
});

test('a snow grid whitens by depth times its shade (the coverage), at its surface heights', () => {
  const grid = { origin: [0, 0, 0], size: [3, 1, 1], dims: [3, 1, 1] };
  const depth = Float32Array.from([0, 2, 2]), heights = Float32Array.from([1, 2, 3]);
  const { positions, colours } = gridTiles(grid, depth, heights, 'snow', Float32Array.from([1, 1, 0.5]));
  assert.deepEqual([0, 1, 2].map((c) => positions[18 * c + 1]), [1, 2, 3]);
  const red = [0, 1, 2].map((c) => colours[18 * c]);
  // Bare ground's grey, full white, and halfway between where half the ground is covered.
  assert.deepEqual(red.map((r) => +r.toFixed(3)), [0.35, 0.95, 0.65]);
});
