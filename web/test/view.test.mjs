import test from 'node:test';
import assert from 'node:assert/strict';
import { FOVY } from '../js/camera.js';
import { EVERY_MS, ViewSync, cameraView, changed } from '../js/view.js';

const close = (a, b, eps = 1e-9) => a.every((x, k) => Math.abs(x - b[k]) < eps);

test('a camera view: the eye, looking at the target, a cone holding the screen diagonal', () => {
  const camera = { target: [1, 2, 3], distance: 4, yaw: 0, pitch: 0 };
  const v = cameraView(camera, 16 / 9, 5000);
  assert.ok(close(v.camera.position, [1, 2, 7]), `${v.camera.position}`);
  assert.ok(close(v.camera.direction, [0, 0, -1]), `${v.camera.direction}`);
  assert.equal(v.budget, 5000);
  // The diagonal's half angle: tan = tan(fovy / 2) * sqrt(1 + aspect^2), wider than the vertical.
  const half = (v.camera.fov_deg * Math.PI) / 360;
  assert.ok(Math.abs(Math.tan(half) - Math.tan(FOVY / 2) * Math.hypot(1, 16 / 9)) < 1e-9);
  assert.ok(v.camera.fov_deg > (FOVY * 180) / Math.PI);
});

test('a view changes when the eye moves 1 % of the distance or turns half a degree', () => {
  const camera = { target: [0, 0, 0], distance: 10, yaw: 0, pitch: 0 };
  const a = cameraView(camera, 1, 100);
  assert.equal(changed(null, a, 10), true);
  assert.equal(changed(a, cameraView({ ...camera, target: [0.05, 0, 0] }, 1, 100), 10), false);
  assert.equal(changed(a, cameraView({ ...camera, target: [0.2, 0, 0] }, 1, 100), 10), true);
  assert.equal(changed(a, cameraView({ ...camera, yaw: 0.02 }, 1, 100), 10), true, 'turned 1.1 degrees (and the eye moved)');
  assert.equal(changed(a, cameraView(camera, 1, 200), 10), true, 'another budget');
});

test('views are sent for scenes over the budget, when the camera moved, at most every EVERY_MS', () => {
  const sent = [];
  const sync = new ViewSync((op) => sent.push(op));
  const camera = { target: [0, 0, 0], distance: 10, yaw: 0, pitch: 0 };
  assert.equal(sync.start(1000, 5000, camera, 1), null, 'within the budget: whole frames');
  sync.update({ ...camera, yaw: 1 }, 1, 0);
  assert.equal(sent.length, 0);
  const first = sync.start(10_000, 5000, camera, 1);
  assert.equal(first.budget, 5000);
  sync.update(camera, 1, 0);
  assert.equal(sent.length, 0, 'the first view went with the query');
  camera.yaw = 0.5;
  sync.update(camera, 1, 1000);
  assert.equal(sent.length, 1);
  assert.equal(sent[0].op, 'view');
  assert.equal(sent[0].budget, 5000);
  camera.yaw = 1;
  sync.update(camera, 1, 1000 + EVERY_MS / 2);
  assert.equal(sent.length, 1, 'too soon');
  sync.update(camera, 1, 1000 + EVERY_MS);
  assert.equal(sent.length, 2);
});
