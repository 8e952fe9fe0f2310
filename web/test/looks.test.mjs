import { test } from 'node:test';
import assert from 'node:assert/strict';
import { MAX_LOOKS, decodeLook, lookChannels, lookCode, lookValues, sceneLooks, splitByLook } from '../js/looks.js';

const MELTING = [{ name: 'temperature' }, { name: 'liquid_fraction' }, { name: 'material' }];
const MATERIALS = [{ name: 'water', look: 'water' }, { name: 'ice', look: 'ice' }, { name: 'ice_melt', look: 'water' }];

test("a scene's looks: each once, water's first as the body", () => {
  assert.deepEqual(sceneLooks(MATERIALS), ['water', 'ice']);
  assert.deepEqual(sceneLooks([{ look: 'ice' }, { look: 'water' }]), ['water', 'ice']);
  assert.deepEqual(sceneLooks([{ look: 'snow' }]), ['snow']);
  assert.deepEqual(sceneLooks([{ look: 'ice' }, { look: 'solid' }]), ['ice', 'solid']);
  assert.deepEqual(sceneLooks([{ look: 'glitter' }]), ['water'], 'a look the page does not know is water');
  assert.deepEqual(sceneLooks(undefined), ['water']);
});

test('materials of several looks ask for the material, and the liquid fraction where ice melts', () => {
  assert.deepEqual(lookChannels('none', MELTING, MATERIALS), ['material', 'liquid_fraction']);
  assert.deepEqual(lookChannels('none', [{ name: 'material' }], MATERIALS), ['material'], 'ice that does not melt');
  assert.deepEqual(lookChannels('temperature', MELTING, MATERIALS), [], 'a colour map replaces the looks');
  assert.deepEqual(lookChannels('none', MELTING, [{ look: 'water' }, { look: 'water' }]), [], 'one look: nothing to tell apart');
  assert.deepEqual(lookChannels('none', [{ name: 'pressure' }], MATERIALS), [], 'a scene without the material channel');
});

test('a look code keeps its look index whatever the rounding, and the fraction towards water', () => {
  for (const [k, f] of [[0, 0], [1, 0], [1, 0.25], [1, 1], [3, 0.5]]) {
    const code = lookCode(k, f);
    for (const c of [code, Math.fround(code / MAX_LOOKS) * MAX_LOOKS]) {
      const d = decodeLook(c);
      assert.equal(d.k, k);
      assert.ok(Math.abs(d.f - f) < 1e-5, `${k} ${f}: ${d.f}`);
    }
  }
  assert.deepEqual(decodeLook(lookCode(2, 7)), { k: 2, f: 1 }, 'fractions are clamped');
});

test('each particle in its look: water as water, ice by its liquid fraction', () => {
  const frame = {
    positions: Float32Array.from([0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0]),
    channels: [
      { name: 'material', values: Uint8Array.from([0, 1, 1, 2]) },
      { name: 'liquid_fraction', values: Float32Array.from([0.5, 0, 0.25, 1]) },
    ],
  };
  // Decoded from float32 codes, to a millionth.
  const decoded = (codes) => [...codes].map((c) => { const { k, f } = decodeLook(c); return [k, Math.round(f * 1e6) / 1e6]; });
  const codes = lookValues(frame, MATERIALS, MELTING);
  assert.deepEqual(decoded(codes), [[0, 0], [1, 0], [1, 0.25], [0, 0]]);
  const solid = lookValues({ positions: frame.positions, channels: [frame.channels[0]] }, MATERIALS, MELTING);
  assert.deepEqual(decoded(solid), [[0, 0], [1, 0], [1, 0], [0, 0]], 'without liquid fractions ice stays ice');
  assert.equal(lookValues({ positions: new Float32Array(3), channels: [] }, MATERIALS, MELTING), null);

  // The surface view's body is the water; the ice goes over it as spheres, codes kept.
  const { body, over } = splitByLook(frame.positions, codes);
  assert.deepEqual([...body.positions], [0, 0, 0, 3, 0, 0]);
  assert.deepEqual([...over.positions], [1, 0, 0, 2, 0, 0]);
  assert.deepEqual([...over.values], [codes[1], codes[2]]);
});
