// Measures what a new user sees first (needs target/release/floe): `floe serve` with its default
// scene (`--scene auto`: sized to the backend at start), the viewer open in headless Chromium,
// Play pressed at the slider's real-time factor of 1; prints the scene the server chose and the
// achieved real-time factor the overlay shows (over the last 3 s) every 3 s for 30 s.
//
//   node tests/browser/measure_default_scene.mjs [--backend cpu|gpu]

import { launchBrowser, startServer } from './harness.mjs';

const backend = process.argv[2] === '--backend' ? process.argv[3] : 'auto';
process.env.FLOE_BACKEND = backend;
const { child, url } = await startServer({ release: true, quiet: true, scene: 'auto' });
const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await page.goto(url);
  await page.waitForFunction(() => /particles\s+[1-9]/.test(document.querySelector('#stats').textContent),
    null, { timeout: 60_000 });
  const scene = await (await fetch(new URL('/api/v1/scenes/1', url))).json();
  console.log(`default scene: ${scene.particles} particles, ${scene.scene.solver.method}, backend ${scene.backend}`);
  await page.click('#play');
  const achieved = [];
  for (let t = 3; t <= 30; t += 3) {
    await page.waitForTimeout(3000);
    const text = await page.textContent('#rtf-achieved');
    const m = /achieved ([\d.e+-]+)/.exec(text);
    if (m) achieved.push(Number(m[1]));
    console.log(`t = ${t} s: ${text}`);
  }
  const sorted = [...achieved].sort((a, b) => a - b);
  console.log(`achieved real-time factor: median ${sorted[sorted.length >> 1]}, min ${sorted[0]}, max ${sorted.at(-1)}`);
} finally {
  await browser.close();
  child.kill('SIGTERM');
}
