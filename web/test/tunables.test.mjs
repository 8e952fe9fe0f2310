import test from 'node:test';
import assert from 'node:assert/strict';
import { sliders, valueAt } from '../js/tunables.js';

const doc = { gravity: [0, -9.81, 0], fluids: [{ xsph: 0.1 }, { xsph: 0 }], solver: { damping: 2 }, snow: { max_viscosity: 200 } };

test('values are found by override paths', () => {
  assert.equal(valueAt(doc, 'fluids[1].xsph'), 0);
  assert.equal(valueAt(doc, 'gravity[1]'), -9.81);
  assert.equal(valueAt(doc, 'solver.missing.deeper'), undefined);
});

test('a slider per bounded number, one per list entry', () => {
  const tunables = [
    { path: 'gravity', unit: 'm/s^2', min: null, max: null },
    { path: 'fluids[*].xsph', unit: '', min: 0, max: 1, about: 'XSPH' },
    { path: 'solver.damping', unit: '1/s', min: 0, max: null },
    { path: 'heat.source', unit: 'W', min: 0, max: 10 },
    // 200 on 0 to 1e9 (steps of 1e7) would snap to 0: no slider.
    { path: 'snow.max_viscosity', unit: 'Pa s', min: 0, max: 1e9 },
  ];
  assert.deepEqual(sliders(tunables, doc), [
    { path: 'fluids[0].xsph', unit: '', min: 0, max: 1, step: 0.01, value: 0.1, about: 'XSPH' },
    { path: 'fluids[1].xsph', unit: '', min: 0, max: 1, step: 0.01, value: 0, about: 'XSPH' },
  ]);
});
