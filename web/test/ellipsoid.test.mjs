// Oriented particles drawn as ellipsoids (web/js/ellipsoid.js): the channels asked for, the
// radii from the scene document, the quaternion's axes, the sprite's size, and the fragment
// shader's ray cast, mirrored here in JavaScript. Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { colourValues } from '../js/colour.js';
import {
  DEFAULT_RADII, boundingRadius, orientationValues, orientedRadii, quaternionAxes, streamedChannels,
} from '../js/ellipsoid.js';

const SOLID_CHANNELS = [
  { name: 'velocity', tag: 1, components: 3 }, { name: 'deformation', tag: 64, components: 1 },
  { name: 'orientation', tag: 65, components: 4 },
];

test('the stream asks for the colour channel, and the orientation where the scene has it', () => {
  assert.deepEqual(streamedChannels('velocity', [{ name: 'velocity' }, { name: 'density' }]), ['velocity']);
  assert.deepEqual(streamedChannels('none', [{ name: 'velocity' }]), []);
  assert.deepEqual(streamedChannels('velocity'), ['velocity']);
  assert.deepEqual(streamedChannels('deformation', SOLID_CHANNELS), ['deformation', 'orientation']);
  assert.deepEqual(streamedChannels('none', SOLID_CHANNELS), ['orientation']);
  // Coloured by the orientation itself: asked for once.
  assert.deepEqual(streamedChannels('orientation', SOLID_CHANNELS), ['orientation']);
});

test('radii come from solid.oriented, in spacings, 0.5 each when not given', () => {
  assert.equal(orientedRadii(null, 0.02), null);
  assert.equal(orientedRadii({ solid: { bodies: [] } }, 0.02), null);
  assert.equal(orientedRadii({ fluids: [] }, 0.02), null);
  const r = orientedRadii({ solid: { oriented: { radii: [0.5, 0.3, 0.25], blend: 'qlerp' } } }, 0.02);
  [0.01, 0.006, 0.005].forEach((x, k) => assert.ok(Math.abs(r[k] - x) < 1e-12, `${r}`));
  assert.deepEqual(orientedRadii({ solid: { oriented: {} } }, 2), DEFAULT_RADII.map((x) => 2 * x));
  assert.deepEqual(orientedRadii({ solid: { oriented: { radii: [1, 0, 1] } } }, 2), [1, 1, 1]);
});

test('the sprite covers the largest radius', () => {
  assert.equal(boundingRadius([0.01, 0.006, 0.006]), 0.01);
  assert.equal(boundingRadius([0.2, 0.7, 0.3]), 0.7);
});

const close = (a, b, eps = 1e-9) => a.every((x, k) => Math.abs(x - b[k]) < eps);

test('a quaternion turns the particle\'s axes', () => {
  assert.deepEqual(quaternionAxes([0, 0, 0, 1]), [[1, 0, 0], [0, 1, 0], [0, 0, 1]]);
  // Zero (a frame without the identity's w): the identity, as the shader falls back to.
  assert.deepEqual(quaternionAxes([0, 0, 0, 0]), [[1, 0, 0], [0, 1, 0], [0, 0, 1]]);
  // 90 degrees about z: x goes to y, y to -x.
  const s = Math.SQRT1_2;
  const [x, y, z] = quaternionAxes([0, 0, s, s]);
  assert.ok(close(x, [0, 1, 0]) && close(y, [-1, 0, 0]) && close(z, [0, 0, 1]), `${[x, y, z]}`);
  // Not quite unit (quantised in the stream): normalised first, so the axes stay orthonormal.
  const axes = quaternionAxes([0.3, -0.2, 0.5, 0.79]);
  for (let i = 0; i < 3; i++) {
    for (let j = 0; j < 3; j++) {
      const dot = axes[i].reduce((sum, v, k) => sum + v * axes[j][k], 0);
      assert.ok(Math.abs(dot - (i === j ? 1 : 0)) < 1e-12, `axes ${i}, ${j}: ${dot}`);
    }
  }
  // Right-handed: x cross y is z.
  const [a, b, c] = axes;
  assert.ok(close([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]], c, 1e-12));
});

/**
 * The fragment shader's ray cast (ELLIPSOID_POINT) with an identity view: the hit's depth
 * offset t and normal under sprite offset d = [dx, dy], or null where the ray misses.
 */
function rayCast(q, radii, [dx, dy]) {
  const axes = quaternionAxes(q);
  const toUnit = (v) => axes.map((axis, k) => (axis[0] * v[0] + axis[1] * v[1] + axis[2] * v[2]) / radii[k]);
  const a = toUnit([dx, dy, 0]), b = toUnit([0, 0, 1]);
  const dot = (u, v) => u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const bb = dot(b, b), ab = dot(a, b), disc = ab * ab - bb * (dot(a, a) - 1);
  if (disc < 0) return null;
  const t = (-ab + Math.sqrt(disc)) / bb;
  const u = a.map((x, k) => (x + t * b[k]) / radii[k]);
  const n = [0, 1, 2].map((i) => axes[0][i] * u[0] + axes[1][i] * u[1] + axes[2][i] * u[2]);
  const len = Math.hypot(...n);
  return { t, normal: n.map((x) => x / len) };
}

test('the ray cast finds the turned ellipsoid\'s outline, front and normal', () => {
  const radii = [0.5, 0.3, 0.2];
  // Unturned: 0.5 wide along x, 0.3 along y, its front 0.2 towards the camera.
  const centre = rayCast([0, 0, 0, 1], radii, [0, 0]);
  assert.ok(Math.abs(centre.t - 0.2) < 1e-12 && close(centre.normal, [0, 0, 1]));
  assert.ok(rayCast([0, 0, 0, 1], radii, [0.49, 0]) && !rayCast([0, 0, 0, 1], radii, [0.51, 0]));
  assert.ok(rayCast([0, 0, 0, 1], radii, [0, 0.29]) && !rayCast([0, 0, 0, 1], radii, [0, 0.31]));
  // Turned 90 degrees about the view axis: the long axis now along y.
  const s = Math.SQRT1_2, turned = [0, 0, s, s];
  assert.ok(rayCast(turned, radii, [0, 0.49]) && !rayCast(turned, radii, [0, 0.51]));
  assert.ok(rayCast(turned, radii, [0.29, 0]) && !rayCast(turned, radii, [0.31, 0]));
  // Turned 90 degrees about y: the long axis along the view, its tip 0.5 in front.
  const facing = rayCast([0, s, 0, s], radii, [0, 0]);
  assert.ok(Math.abs(facing.t - 0.5) < 1e-12 && close(facing.normal, [0, 0, 1]), JSON.stringify(facing));
  // At the rim the normal lies in the view plane, pointing out.
  const rim = rayCast([0, 0, 0, 1], radii, [0.5 - 1e-9, 0]);
  assert.ok(rim.normal[0] > 0.99, JSON.stringify(rim));
  // The point found lies on the surface for any turn.
  const q = [0.3, -0.2, 0.5, 0.79], len = Math.hypot(...q), axes = quaternionAxes(q);
  const hit = rayCast(q, radii, [0.1, -0.05]);
  const p = [0.1, -0.05, hit.t];
  const local = axes.map((axis, k) => (axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2]) / radii[k]);
  assert.ok(Math.abs(Math.hypot(...local) - 1) < 1e-9, `${local} (q of length ${len})`);
});

test('a frame\'s orientations are found by the tag the scene gives them', () => {
  const frame = {
    positions: new Float32Array(6),
    channels: [
      { name: 'velocity', tag: 1, components: 3, values: new Float32Array([3, 4, 0, 0, 0, 0]) },
      { name: 'channel 65', tag: 65, components: 4, values: new Float32Array([0, 0, 0, 1, 0, 0, 0.5, -0.5]) },
    ],
  };
  assert.deepEqual([...orientationValues(frame, SOLID_CHANNELS)], [0, 0, 0, 1, 0, 0, 0.5, -0.5]);
  // Colouring by velocity still reads its own channel.
  assert.deepEqual([...colourValues(frame, 'velocity', SOLID_CHANNELS)], [5, 0]);
  // Without the scene's tags, or without the channel: none.
  assert.equal(orientationValues(frame), null);
  assert.equal(orientationValues({ positions: frame.positions, channels: [frame.channels[0]] }, SOLID_CHANNELS), null);
  // Values that do not match the particles are not drawn.
  const short = { ...frame.channels[1], values: new Float32Array(4) };
  assert.equal(orientationValues({ positions: frame.positions, channels: [short] }, SOLID_CHANNELS), null);
});
