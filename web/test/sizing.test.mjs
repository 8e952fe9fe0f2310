import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fullSizeLabel, fullSizeRequest, sizedRealTime, sizingText } from '../js/sizing.js';

const SIZING = { spacing: 0.0175, particles: 1210, real_time_factor: 1.1, full_spacing: 0.01, full_particles: 6537 };

test('a sized scene says what the server chose and its full size', () => {
  assert.equal(sizingText(SIZING), '1,210 of 6,537 particles (1.75 cm spacing, full size 1 cm), sized for this machine');
  assert.equal(sizingText({ ...SIZING, spacing: 0.023333333, particles: 1154, full_particles: 17037 }),
    '1,154 of 17,037 particles (2.33 cm spacing, full size 1 cm), sized for this machine');
  assert.equal(sizingText({ ...SIZING, spacing: 0.01, particles: 6537 }),
    '6,537 particles (1 cm spacing, the full size), sized for this machine');
  assert.equal(sizingText(undefined), null, 'a scene its creator sized says nothing new');
  assert.equal(sizedRealTime(SIZING), '; sized for 1.1');
  assert.equal(sizedRealTime(null), '');
});

test('the full size is the same preset at its own spacing', () => {
  assert.deepEqual(fullSizeRequest({ name: 'bunny', sizing: SIZING }), { preset: 'bunny', overrides: ['particle_spacing=0.01'] });
  assert.equal(fullSizeRequest({ name: 'bunny', sizing: { ...SIZING, spacing: 0.01 } }), null, 'sized at its full size already');
  assert.equal(fullSizeRequest({ name: 'bunny' }), null);
  assert.equal(fullSizeRequest(null), null);
  assert.equal(fullSizeLabel(SIZING), 'Full size (6,537 particles)');
});
