// Measures the viewer in headless Chromium on a large scene: render frames per
// second and frames received per second, as the stats overlay reports them.
//
//   node tests/browser/measure_fps.mjs [particles]      (default 200000; needs target/release/floe)
//
// Software GL (SwiftShader) on the CPU: the figure is for this machine without a GPU.

import { spawn } from 'node:child_process';
import { chromium } from 'playwright-core';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const floe = process.env.FLOE_BIN ?? path.join(root, 'target/release/floe');
const particles = Number(process.argv[2] ?? 200000);
const spacing = 0.5 / Math.round(Math.cbrt(particles));

const child = spawn(floe, ['serve', '--http', '127.0.0.1:0', '--grpc', '127.0.0.1:0', '--scene', 'none'],
  { cwd: root, stdio: ['ignore', 'pipe', 'ignore'] });
const url = await new Promise((resolve, reject) => {
  let out = '';
  child.on('exit', (c) => reject(new Error(`floe serve exited with ${c}`)));
  child.stdout.on('data', (d) => { out += d; const m = out.match(/Floe viewer: (http:\/\/\S+)/); if (m) resolve(m[1]); });
});
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await page.goto(url);
  const scene = await page.evaluate(async (s) => (await fetch('/api/v1/scenes', {
    method: 'POST', headers: { 'content-type': 'application/json' },
    body: JSON.stringify({ preset: 'dam_break', overrides: [`particle_spacing=${s}`] }),
  })).json(), spacing);
  await page.reload();
  await page.click('#play');
  await page.waitForTimeout(5000);
  const read = () => page.evaluate(() => document.querySelector('#stats').textContent);
  const num = (text, label) => Number(new RegExp(`${label}\\s+([\\d.]+)`).exec(text)?.[1]);
  const t0 = await read();
  await page.waitForTimeout(10000);
  const t1 = await read();
  console.log(`| particles | render fps | frames received/s | bytes/frame | decode ms |`);
  console.log(`|---:|---:|---:|---:|---:|`);
  console.log(`| ${scene.particles} | ${num(t1, 'render')} | ${((num(t1, 'frames') - num(t0, 'frames')) / 10).toFixed(1)} | ${num(t1, 'bytes/frm')} | ${num(t1, 'decode')} |`);
} finally {
  await browser.close();
  child.kill('SIGTERM');
}
