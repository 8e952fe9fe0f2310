// The wall outline's geometry (web/js/outline.js). Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { boxEdges, wallLines } from '../js/outline.js';

test('a box has 12 edges, each along one axis, covering all 8 corners', () => {
  const min = [0, -1, 0.5], max = [2, 1.2, 0.75];
  const e = boxEdges(min, max);
  assert.equal(e.length, 12 * 2 * 3);
  const perAxis = [0, 0, 0];
  const corners = new Set();
  for (let i = 0; i < e.length; i += 6) {
    const a = e.slice(i, i + 3), b = e.slice(i + 3, i + 6);
    const differ = [0, 1, 2].filter((k) => a[k] !== b[k]);
    assert.equal(differ.length, 1, `edge ${i / 6} runs along one axis`);
    const k = differ[0];
    assert.deepEqual([Math.min(a[k], b[k]), Math.max(a[k], b[k])], [Math.fround(min[k]), Math.fround(max[k])]);
    perAxis[k] += 1;
    corners.add(a.join()).add(b.join());
  }
  assert.deepEqual(perAxis, [4, 4, 4]);
  assert.equal(corners.size, 8);
});

test('only box walls are outlined', () => {
  const scene = {
    boundaries: [
      { kind: 'box', min: [0, 0, 0], max: [1, 1, 1] },
      { kind: 'plane', center: [0, 0, 0], normal: [0, 1, 0], size: [1, 1] },
      { kind: 'box', min: [2, 0, 0], max: [3, 1, 1] },
    ],
  };
  assert.equal(wallLines(scene).length, 2 * 72);
  assert.equal(wallLines(null).length, 0);
  assert.equal(wallLines({}).length, 0);
});
