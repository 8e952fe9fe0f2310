// Measures the viewer in headless Chromium on large scenes (needs target/release/floe):
//
//   node tests/browser/measure_fps.mjs [particles]          render fps of both views (default 200000)
//   node tests/browser/measure_fps.mjs --paused [particles] the same with the scene paused (the
//                                                           solver not sharing the CPU)
//   FLOE_WEB=DIR node tests/browser/measure_fps.mjs [particles]   the same for another viewer
//                                                           (an older one: its single view)
//   node tests/browser/measure_fps.mjs --scrub [particles] [frames]
//                                                           replay: seek times in a floectl recording
//                                                           (default 100000 particles, 300 frames;
//                                                           needs target/release/floectl)
//
// Render: the dam break runs while the camera orbits (a drag across the view), so every frame
// is drawn anew (the viewer otherwise draws only when something changed); "render fps" is frames
// drawn per second as the overlay counts them, at the resolution the viewer keeps while the
// picture moves (printed beside it, web/js/resolution.js), with the points it drew. Scrub: the timeline is set to 40 frames spread
// over the recording, one at a time; "seek" is the worker's time to decode the frame (and the
// frames before it back to a kept state), "shown" the time from the slider's input event until
// the frame's label changes (the frame reached the page, which may have been busy drawing),
// "drawn" until two animation frames later (uploaded and drawn). Software GL (SwiftShader) on
// the CPU: the figures are for a machine without a GPU.

import { spawn } from 'node:child_process';
import { mkdtemp, rm, stat } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { createScene, freePort, launchBrowser, root, startServer } from './harness.mjs';

const args = process.argv.slice(2);
const scrub = args[0] === '--scrub';
const paused = args[0] === '--paused';
if (scrub || paused) args.shift();
const particles = Number(args[0] ?? (scrub ? 100000 : 200000));
const spacing = 0.5 / Math.round(Math.cbrt(particles));
const grpc = `127.0.0.1:${await freePort()}`;
const { child, url } = await startServer({ grpc, release: true, quiet: true });
const browser = await launchBrowser();
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const scene = await createScene(url, 'dam_break', [`particle_spacing=${spacing}`]);
  await page.goto(url);
  await page.waitForFunction((n) => new RegExp(`particles\\s+${n}\\b`).test(document.querySelector('#stats').textContent),
    scene.particles, { timeout: 60_000 });
  if (scrub) await measureScrub(page, scene, Number(args[1] ?? 300));
  else await measureRender(page, scene);
} finally {
  await browser.close();
  child.kill('SIGTERM');
}

async function measureRender(page, scene) {
  if (!paused) await page.click('#play');
  const read = () => page.textContent('#stats');
  const num = (text, label) => Number(new RegExp(`${label}\\s+([\\d.]+)`).exec(text)?.[1]);
  console.log(`| particles | view | render fps (orbiting; median of 5, range) | resolution while moving | drawn | frames received/s | bytes/frame | decode ms |   scene ${paused ? 'paused' : 'running'}`);
  console.log('|---:|---|---:|---:|---:|---:|---:|---:|');
  const views = (await page.$('#view-mode')) ? ['spheres', 'surface'] : ['spheres (the only view)'];
  for (const view of views) {
    if (views.length > 1) await page.selectOption('#view-mode', view);
    await page.mouse.move(700, 400);
    await page.mouse.down();
    let x = 700, dir = 1;
    const orbit = async (ms) => {
      for (const end = Date.now() + ms; Date.now() < end;) {
        x += 4 * dir;
        if (x > 1000 || x < 400) dir = -dir;
        await page.mouse.move(x, 400);
        await page.waitForTimeout(25);
      }
    };
    await orbit(4000);
    const t0 = await read();
    const fps = [];
    for (let i = 0; i < 5; i++) {
      await orbit(2000);
      fps.push(num(await read(), 'render'));
    }
    const t1 = await read();
    await page.mouse.up();
    fps.sort((a, b) => a - b);
    const received = (num(t1, 'frames') - num(t0, 'frames')) / 10;
    // Where the viewer lowers the resolution while the picture moves (web/js/resolution.js), and
    // how many points it draws (cull.js), as the overlay says at the end.
    const resolution = /at (\d+) % resolution/.exec(t1)?.[1] ?? '100';
    const drawn = /\((\d+) drawn\)/.exec(t1)?.[1] ?? scene.particles;
    console.log(`| ${scene.particles} | ${view} | ${fps[2]} (${fps[0]}-${fps[4]}) | ${resolution} % | ${drawn} | ${received.toFixed(1)} | ${num(t1, 'bytes/frm')} | ${num(t1, 'decode')} |`);
  }
}

async function measureScrub(page, scene, frames) {
  const dir = await mkdtemp(path.join(tmpdir(), 'floe-scrub-'));
  const file = path.join(dir, 'scene.rec');
  try {
    const floectl = process.env.FLOECTL ?? path.join(root, 'target/release/floectl');
    await page.click('#play');
    await run(floectl, ['--server', `http://${grpc}`, 'record', String(scene.scene_id), '--out', file, '--frames', String(frames), '--fps', '30']);
    await page.click('#pause');
    await page.setInputFiles('#recording-file', file);
    await page.waitForFunction(() => document.querySelector('#tl-label').textContent.startsWith('frame 1 /'), null, { timeout: 120_000 });
    await page.waitForFunction(() => document.querySelector('#tl-progress').dataset.indexMs !== undefined, null, { timeout: 600_000 });
    const indexSeconds = Number(await page.getAttribute('#tl-progress', 'data-index-ms')) / 1000;
    const total = Number(/frame 1 \/ (\d+)/.exec(await page.textContent('#tl-label'))[1]);
    // 40 frames spread over the recording in a scrambled order (never frame 0, shown already).
    const targets = Array.from({ length: 40 }, (_, i) => 1 + Math.floor((((i + 1) * 7919) % 997) / 997 * (total - 1)));
    const seek = [], shown = [], drawn = [];
    for (const k of targets) {
      const [w, a, b] = await page.evaluate((frame) => new Promise((resolve) => {
        const slider = document.querySelector('#tl-slider'), label = document.querySelector('#tl-label');
        const t0 = performance.now();
        slider.value = String(frame);
        slider.dispatchEvent(new Event('input'));
        const want = `frame ${frame + 1} /`;
        const check = () => {
          if (!label.textContent.startsWith(want)) return setTimeout(check, 1);
          const t1 = performance.now();
          requestAnimationFrame(() => requestAnimationFrame(() => resolve([Number(label.dataset.seekMs), t1 - t0, performance.now() - t0])));
        };
        check();
      }), k);
      seek.push(w);
      shown.push(a);
      drawn.push(b);
    }
    const stats = (v) => { const s = [...v].sort((x, y) => x - y); return `${s[s.length >> 1].toFixed(0)} / ${s.at(-1).toFixed(0)}`; };
    const view = await page.inputValue('#view-mode');
    console.log(`| particles | frames | file MB | indexing s | seeks | seek ms in the worker | shown ms | drawn ms (${view} view) |`);
    console.log('|---:|---:|---:|---:|---:|---:|---:|---:|');
    const { size } = await stat(file);
    console.log(`| ${scene.particles} | ${total} | ${(size / 1e6).toFixed(1)} | ${indexSeconds.toFixed(1)} | ${targets.length} | ${stats(seek)} | ${stats(shown)} | ${stats(drawn)} |`);
    console.log('(median / max of each; every seek in order, ms in the worker / shown / drawn:)');
    console.log(targets.map((k, i) => `${k}: ${seek[i].toFixed(0)}/${shown[i].toFixed(0)}/${drawn[i].toFixed(0)}`).join(', '));
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
}

function run(cmd, argv) {
  return new Promise((resolve, reject) => {
    const p = spawn(cmd, argv, { stdio: ['ignore', 'ignore', 'inherit'] });
    p.on('error', reject);
    p.on('exit', (code) => (code === 0 ? resolve() : reject(new Error(`${cmd} exited with ${code}`))));
  });
}
