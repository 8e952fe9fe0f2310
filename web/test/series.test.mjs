// Plot series bookkeeping and CSV (web/js/series.js), colour modes (web/js/colour.js) and the
// particle size (web/js/spacing.js). Run: node --test web/test/
import assert from 'node:assert/strict';
import test from 'node:test';
import { DEFAULT_CHANNELS, colourModes, colourValues, valueRange } from '../js/colour.js';
import { SeriesSet } from '../js/series.js';
import { RADIUS_PER_SPACING, estimateSpacing, physicalRadius } from '../js/spacing.js';

const status = (sim_time, extra = {}) => ({ sim_time, state: 'running', steps_per_second: 50, dt: 1e-3, ...extra });

test('series take a sample when simulated time moves on, with the achieved real-time factor', () => {
  const s = new SeriesSet();
  assert.equal(s.add(status(0), 10), true);
  assert.equal(s.add(status(0), 10.5), false, 'no progress, no sample');
  assert.equal(s.add(status(0.01), 11), true);
  assert.equal(s.add(status(0.03, { steps_per_second: 60 }), 12), true);
  assert.deepEqual(s.sim, [0, 0.01, 0.03]);
  const rtf = s.values.get('real_time_factor');
  assert.ok(Number.isNaN(rtf[0]));
  assert.ok(Math.abs(rtf[1] - 0.02) < 1e-12, `${rtf[1]}`);
  assert.ok(Math.abs(rtf[2] - 0.02) < 1e-12);
  assert.deepEqual(s.values.get('steps_per_second'), [50, 50, 60]);
  assert.ok(Math.abs(s.recentRealTime(5) - 0.03 / 2) < 1e-12, 'from the first running sample in the window');
  assert.ok(Math.abs(s.recentRealTime(1) - 0.02) < 1e-12);
  // Paused in between: no real-time factor across the pause.
  s.add({ ...status(0.03), state: 'paused' }, 13);
  s.add(status(0.04), 20);
  assert.ok(Number.isNaN(rtf.at(-1)));
  assert.ok(Number.isNaN(s.recentRealTime(5)));
});

test('measures add series as the scene reports them; a step back in time starts afresh', () => {
  const s = new SeriesSet();
  s.add(status(0.1), 0);
  s.add(status(0.2, { measures: { kinetic_energy: { value: 2.5, unit: 'J' } } }), 1);
  s.add(status(0.3, { measures: { kinetic_energy: { value: 3, unit: 'J' }, mean_temperature: { value: 290, unit: 'K' } } }), 2);
  assert.deepEqual(s.columns.map((c) => c.name), ['steps_per_second', 'dt', 'real_time_factor', 'kinetic_energy', 'mean_temperature']);
  assert.deepEqual(s.columns.at(-1), { name: 'mean_temperature', label: 'mean temperature', unit: 'K' });
  assert.deepEqual(s.values.get('kinetic_energy'), [NaN, 2.5, 3]);
  assert.deepEqual(s.values.get('mean_temperature'), [NaN, NaN, 290]);
  s.add(status(0.05), 3);
  assert.equal(s.length, 1);
  assert.deepEqual(s.sim, [0.05]);
  assert.equal(s.columns.length, 3, 'measures go with the old run');
});

test('the CSV holds every sample and series, units in the header, empty cells for gaps', () => {
  const s = new SeriesSet();
  s.add(status(0.1), 5);
  s.add(status(0.2, { measures: { 'front, x': { value: 0.75, unit: 'm' } } }), 6);
  const lines = s.csv().split('\r\n');
  assert.equal(lines[0], 'wall_time (s),sim_time (s),steps_per_second (1/s),dt (s),real_time_factor,"front, x (m)"');
  assert.equal(lines[1], '0,0.1,50,0.001,,');
  assert.equal(lines[2], '1,0.2,50,0.001,0.1,0.75');
  assert.equal(lines[3], '');
  assert.equal(lines.length, 4);
});

test('the oldest samples go beyond the capacity', () => {
  const s = new SeriesSet(3);
  for (let i = 1; i <= 5; i++) s.add(status(i / 10), i);
  assert.deepEqual(s.sim, [0.3, 0.4, 0.5]);
  assert.equal(s.values.get('dt').length, 3);
});

test('colour modes come from a channel list; vectors colour by magnitude', () => {
  assert.deepEqual(colourModes(DEFAULT_CHANNELS).map((m) => [m.value, m.label]), [
    ['velocity', 'speed (m/s)'], ['density', 'density (kg/m³)'], ['pressure', 'pressure (Pa)'], ['none', 'none'],
  ]);
  assert.deepEqual(colourModes([{ name: 'temperature', unit: 'K', components: 1 }, { name: 'vorticity', unit: '1/s', components: 3 }])
    .map((m) => m.label), ['temperature (K)', '|vorticity| (1/s)', 'none']);
  const density = new Float32Array([1000, 990]);
  const frame = {
    positions: new Float32Array(6),
    channels: [
      { name: 'velocity', components: 3, values: new Float32Array([3, 4, 0, 0, 0, -2]) },
      { name: 'density', components: 1, values: density },
    ],
  };
  assert.deepEqual(colourValues(frame, 'velocity'), new Float32Array([5, 2]));
  assert.equal(colourValues(frame, 'density'), density);
  assert.equal(colourValues(frame, 'pressure'), null);
  assert.equal(colourValues(frame, 'none'), null);
  // A module's channel under its per-scene tag, named by the scene's channel list.
  const viscosity = new Float32Array([200, 5]);
  const dynamic = { ...frame, channels: [...frame.channels, { tag: 64, name: 'channel 64', components: 1, values: viscosity }] };
  assert.equal(colourValues(dynamic, 'viscosity'), null);
  assert.equal(colourValues(dynamic, 'viscosity', [{ name: 'viscosity', tag: 64 }]), viscosity);
  assert.deepEqual(valueRange(new Float32Array([2, NaN, -1, Infinity, 7])), [-1, 7]);
  assert.deepEqual(valueRange([]), [0, 0]);
});

test('particles are drawn as spheres of their volume; a lattice gives back its spacing', () => {
  assert.ok(Math.abs((4 / 3) * Math.PI * physicalRadius(0.02) ** 3 - 0.02 ** 3) < 1e-15);
  assert.ok(Math.abs(RADIUS_PER_SPACING - 0.6204) < 1e-4);
  const h = 0.025, side = 12, lattice = new Float32Array(3 * side ** 3);
  let i = 0;
  for (let x = 0; x < side; x++) for (let y = 0; y < side; y++) for (let z = 0; z < side; z++) lattice.set([x * h, 1 + y * h, z * h], 3 * i++);
  assert.ok(Math.abs(estimateSpacing(lattice) - h) < 1e-6, `${estimateSpacing(lattice)}`);
  // A flat sheet and a few particles far off (a splash) change nothing.
  const sheet = new Float32Array(3 * 40 * 40 + 6);
  for (let k = 0; k < 1600; k++) sheet.set([(k % 40) * h, 0.5, Math.floor(k / 40) * h], 3 * k);
  sheet.set([5, 5, 5, -3, 2, 1], 4800);
  assert.ok(Math.abs(estimateSpacing(sheet) - h) < 1e-6, `${estimateSpacing(sheet)}`);
  assert.equal(estimateSpacing(new Float32Array(3)), 0);
});
