import test from 'node:test';
import assert from 'node:assert/strict';
import { realTime, statsText } from '../js/overlay.js';

test('the real-time factor: achieved against asked, slow below 0.9 of it', () => {
  const running = { state: 'running' };
  assert.deepEqual(realTime({ state: 'paused' }, 0.5, 1), { text: '', slow: false });
  assert.deepEqual(realTime(running, NaN, 1), { text: 'measuring', slow: false });
  assert.deepEqual(realTime(running, 0.95, 1), { text: '0.95 of 1.0 asked', slow: false });
  assert.deepEqual(realTime(running, 0.5, 1), { text: '0.50 of 1.0 asked (cannot keep up)', slow: true });
  assert.deepEqual(realTime(running, 3.2, null), { text: '3.2', slow: false });
});

test('the overlay says what is drawn, live or replayed', () => {
  const renderer = { view: 'spheres', count: 1000, drawnCount: 800, oriented: false, resolution: { moving: 0.5 } };
  const stream = { renderFps: 59.6, frames: 12, skipped: 2, lastBytes: 3000, decodeMs: 1.234 };
  const status = { backend: 'cpu', sim_time: 0.25, state: 'running', steps_per_second: 410.2, dropped_frames: 3 };
  const live = statsText({ renderer, status, replay: null, realTime: { text: '0.95' }, stream, others: ['ice  5 frames'] });
  assert.deepEqual(live.split('\n'), [
    'render     60 fps (spheres) at 50 % resolution while moving',
    'particles  1000 on cpu (800 drawn)',
    'sim time   0.250 s (running)',
    'real time  0.95',
    'steps/s    410',
    'frames     12 (2 skipped, decoder busy)',
    'bytes/frm  3000 (3.00 B/particle)',
    'decode     1.23 ms',
    'dropped    3',
    'ice  5 frames',
  ]);
  const sizing = { spacing: 0.0175, particles: 1210, real_time_factor: 1.1, full_spacing: 0.01, full_particles: 6537 };
  const sized = statsText({ renderer, status, replay: null, realTime: { text: '0.95' }, stream, others: [], sizing });
  assert.deepEqual(sized.split('\n').slice(1, 5), [
    'particles  1000 on cpu (800 drawn)',
    'size       1,210 of 6,537 particles (1.75 cm spacing, full size 1 cm), sized for this machine',
    'sim time   0.250 s (running)',
    'real time  0.95; sized for 1.1',
  ]);
  const viewed = statsText({ renderer, status, replay: null, realTime: { text: '0.95' }, stream, others: [], inView: 4000000 });
  assert.equal(viewed.split('\n')[1], "particles  1000 of 4000000 (the camera's view) on cpu (800 drawn)");
  const replayed = statsText({ renderer: { ...renderer, drawnCount: 1000, resolution: { moving: 1 } }, status: null,
    replay: ['replay     frame 3 of 9'], realTime: { text: '' }, stream: { ...stream, renderFps: 0 }, others: ['ice'] });
  assert.deepEqual(replayed.split('\n'), ['render     idle (spheres)', 'particles  1000', 'replay     frame 3 of 9', 'decode     1.23 ms']);
});
