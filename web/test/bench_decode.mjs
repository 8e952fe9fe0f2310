// Decode throughput of the JavaScript frame decoder (web/js/codec/) on the golden frames.
//
//   node web/test/bench_decode.mjs [--seconds S] [extra.bin ...]
//
// Each golden frame is decoded repeatedly (identity-ordered frames as the stream keyframe,
// delta, linear delta, so each delta frame has its base), timing every decode; the best of
// 5 passes is reported per frame in M particles/s. Extra .bin files (unordered frames or
// keyframes) are timed the same way, decoded on their own. The golden frames are small
// (200-300 particles), so per-frame overheads weigh more than on real frames of 10^5 particles.
// Under `node --test` (which runs every file in web/test/) it only makes a short smoke run.
import { readFileSync } from 'node:fs';
import { Decoder } from '../js/codec/index.js';

const smoke = process.env.NODE_TEST_CONTEXT !== undefined;
const args = process.argv.slice(2);
const secondsAt = args.indexOf('--seconds');
const seconds = smoke ? 0.02 : secondsAt >= 0 ? Number(args.splice(secondsAt, 2)[1]) : 0.5;
const passes = smoke ? 1 : 5;
const DATA = new URL('../../proto/testdata/', import.meta.url);
const golden = (name) => ({ name, bytes: new Uint8Array(readFileSync(new URL(`${name}.bin`, DATA))) });

/** Groups decoded in order on one decoder, each frame timed on its own. */
const groups = [
  [golden('unordered_positions')],
  [golden('unordered_channels')],
  [golden('identity_keyframe'), golden('identity_delta'), golden('identity_linear')],
  ...args.map((path) => [{ name: path, bytes: new Uint8Array(readFileSync(path)) }]),
];

const results = [];
let allParticles = 0;
let allNs = 0;
for (const group of groups) {
  const decoder = new Decoder();
  const particles = group.map((f) => decoder.decode(f.bytes).header.particleCount);
  const best = group.map(() => Infinity);
  for (let pass = 0; pass < passes; pass++) {
    const ns = group.map(() => 0n);
    let rounds = 0;
    const end = performance.now() + seconds * 1000;
    while (performance.now() < end) {
      for (let r = 0; r < 50; r++) {
        for (let i = 0; i < group.length; i++) {
          const t0 = process.hrtime.bigint();
          decoder.decode(group[i].bytes);
          ns[i] += process.hrtime.bigint() - t0;
        }
      }
      rounds += 50;
    }
    group.forEach((_, i) => { best[i] = Math.min(best[i], Number(ns[i]) / rounds); });
  }
  group.forEach((f, i) => {
    results.push({ frame: f.name, particles: particles[i], bytes: f.bytes.length, 'µs/frame': best[i] / 1e3,
      'M particles/s': particles[i] / best[i] * 1e3 });
    allParticles += particles[i];
    allNs += best[i];
  });
}

console.log(`floe frame decode, JavaScript (Node ${process.version}), best of ${passes} pass(es) of ${seconds} s per frame`);
console.log('Golden frames are small (200-300 particles): per-frame overheads dominate more than on real frames.');
if (smoke) console.log('(smoke run under node --test: timings are not meaningful)');
console.table(results.map((r) => ({ ...r, 'µs/frame': +r['µs/frame'].toFixed(2), 'M particles/s': +r['M particles/s'].toFixed(1) })));
console.log(`all frames together: ${(allParticles / allNs * 1e3).toFixed(1)} M particles/s`);
