import { test } from 'node:test';
import assert from 'node:assert/strict';
import { phaseChannels, phaseLooks, phaseValues } from '../js/phase.js';
import { LOOKS } from '../js/render.js';

const MELTING = [{ name: 'temperature' }, { name: 'liquid_fraction' }, { name: 'material' }];
const MATERIALS = [{ name: 'water', look: 'water' }, { name: 'ice', look: 'ice' }, { name: 'ice_melt', look: 'water' }];

test('a melting scene asks for materials and liquid fractions only without a colour map', () => {
  assert.deepEqual(phaseChannels('none', MELTING), ['material', 'liquid_fraction']);
  assert.deepEqual(phaseChannels('temperature', MELTING), []);
  assert.deepEqual(phaseChannels('none', [{ name: 'pressure' }]), []);
});

test('ice is drawn by its liquid fraction, water as water', () => {
  const frame = {
    positions: new Float32Array(12),
    channels: [
      { name: 'material', values: Uint8Array.from([0, 1, 1, 2]) },
      { name: 'liquid_fraction', values: Float32Array.from([0, 0, 0.25, 1]) },
    ],
  };
  assert.deepEqual([...phaseValues(frame, MATERIALS, MELTING)], [1, 0, 0.25, 1]);
  assert.equal(phaseValues({ positions: new Float32Array(3), channels: [] }, MATERIALS, MELTING), null);
});

test('the looks run from the ice to water', () => {
  assert.deepEqual(phaseLooks(MATERIALS, LOOKS), { from: LOOKS.ice.rgb, to: LOOKS.water.rgb });
  assert.equal(phaseLooks([{ look: 'water' }], LOOKS), null);
});
