// The viewer's features in headless Chromium, on one small dam break (4096 particles): a clean
// load, the camera framing the scene, particles at their size, the surface view, plots and
// their CSV, recording and replay (the page's own recording and one `floectl record` made),
// the help overlay, errors beside the control used, and the page at phone width. Screenshots go
// to target/viewer-*.png.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import { canvasSummary, createScene, launchBrowser, root, startServer, stat, statAtLeast, watchProblems } from './harness.mjs';

const shot = (page, name) => page.screenshot({ path: path.join(root, `target/viewer-${name}.png`) });
const text = (page, selector) => page.textContent(selector);
/** Waits for the next frames to be drawn. */
const settle = (page) => page.waitForTimeout(800);

test('the viewer: views, plots, record and replay, help, errors, phone width', { timeout: 300_000 }, async (t) => {
  const { child: server, url } = await startServer();
  const browser = await launchBrowser();
  try {
    await createScene(url, 'dam_break', ['particle_spacing=0.03125']);
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    const problems = watchProblems(page);
    await page.goto(url);
    await statAtLeast(page, 'particles', 4096);
    await statAtLeast(page, 'frames', 1);
    let spheres;

    await t.test('it loads without an error or a failed request, and frames the scene beside the panel', async () => {
      await settle(page);
      assert.deepEqual(problems, []);
      const panel = await page.locator('#panel').boundingBox();
      const { scene, width, height } = await canvasSummary(page);
      const free = width - (panel.x + panel.width);
      assert.ok(scene.x0 >= panel.x + panel.width - 1, `the scene starts under the panel, at x = ${scene.x0}`);
      assert.ok(scene.x1 <= width && scene.y0 >= 0 && scene.y1 <= height, `the scene runs off the view: ${JSON.stringify(scene)}`);
      assert.ok(scene.x1 - scene.x0 > 0.6 * free || scene.y1 - scene.y0 > 0.6 * height,
        `the scene fills too little of the view: ${JSON.stringify(scene)} in ${free} x ${height}`);
    });

    await t.test('spheres at their physical size: the resting column shows nothing through it', async () => {
      await page.selectOption('#view-mode', 'spheres');
      await settle(page);
      await shot(page, 'spheres');
      const s = await canvasSummary(page);
      assert.ok(s.fluid > 2000, `only ${s.fluid} fluid pixels`);
      assert.ok(s.gaps < 0.03 * s.fluid, `${s.gaps} background pixels show between particles (${s.fluid} fluid pixels)`);
      spheres = s;
    });

    await t.test('the surface view draws the water as one body, in water colours', async () => {
      await page.selectOption('#view-mode', 'surface');
      await page.waitForFunction(() => /render .*\(surface\)/.test(document.querySelector('#stats').textContent));
      await settle(page);
      await shot(page, 'surface');
      const s = await canvasSummary(page);
      assert.ok(s.fluid > 0.8 * spheres.fluid, `${s.fluid} water pixels, ${spheres.fluid} in the sphere view`);
      assert.ok(s.gaps < 0.01 * s.fluid, `${s.gaps} gaps in the water`);
      const [r, g, b] = s.colour;
      assert.ok(b > r + 40 && g > r, `the water is not blue: mean colour ${s.colour.map(Math.round)}`);
    });

    await t.test('while the picture moves slower than asked it is drawn at a lower resolution, sharp once still', async () => {
      // Asking for more frames a second than software GL draws makes the view lower its
      // resolution while the scene plays (web/js/resolution.js); paused, it is drawn sharp.
      await page.goto(`${url}?fps=500`);
      await statAtLeast(page, 'frames', 1);
      await page.selectOption('#view-mode', 'surface');
      const canvasSize = () => page.evaluate(() => {
        const c = document.querySelector('#view');
        return { drawn: [c.width, c.height], full: [Math.round(c.clientWidth * devicePixelRatio), Math.round(c.clientHeight * devicePixelRatio)] };
      });
      await page.click('#play');
      let smallest = Infinity;
      for (let i = 0; i < 40 && smallest > 0.7; i++) {
        await page.waitForTimeout(200);
        const { drawn, full } = await canvasSize();
        smallest = Math.min(smallest, drawn[0] / full[0]);
      }
      assert.ok(smallest <= 0.7, `the canvas stayed at ${smallest} of its resolution while the scene played`);
      assert.match(await text(page, '#stats'), /render .*\(surface\) at \d+ % resolution while moving/);
      await page.click('#pause');
      await settle(page);
      await settle(page);
      const { drawn, full } = await canvasSize();
      assert.deepEqual(drawn, full, 'the still picture is drawn at full resolution');
      await shot(page, 'surface-after-moving');
      assert.ok((await canvasSummary(page)).fluid > 0.5 * spheres.fluid, 'the water is drawn');
      // Until the reset's request has finished: leaving the page while its body is in flight aborts it.
      await Promise.all([page.waitForEvent('requestfinished', (r) => r.url().endsWith('/reset')), page.click('#reset')]);
      await page.goto(url);
      await statAtLeast(page, 'frames', 1);
    });

    await t.test('plots: a live series per statistic with its unit, and the CSV of them', async () => {
      await page.click('#plots-open');
      await page.click('#play');
      await page.waitForFunction(() => document.querySelectorAll('#plots figure').length >= 3, null, { timeout: 30_000 });
      // The achieved real-time factor next to the one asked for, once two running samples came.
      await page.waitForFunction(() => /real time\s+[\d.e-]+ of 1\.0 asked/.test(document.querySelector('#stats').textContent),
        null, { timeout: 30_000 });
      const captions = await page.locator('#plots figcaption').allTextContents();
      assert.match(captions[0], /^steps per second \(1\/s\): [\d.e+-]+$/);
      assert.match(captions[1], /^time step \(s\): [\d.e+-]+$/);
      assert.match(captions[2], /^real-time factor \(achieved\): [\d.e+-]+$/);
      assert.match(await text(page, '#rtf-achieved'), /^achieved [\d.e-]+ of 1\.0 asked/);
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#plots .plots-csv')]);
      assert.match(download.suggestedFilename(), /^floe-scene-1-stats\.csv$/);
      const lines = (await readFile(await download.path(), 'utf8')).trim().split('\r\n');
      // The fixed statistics, the scene's measures with their units, then its pressure
      // solves' residuals and iterations (the dam break's preset runs DFSPH).
      assert.equal(lines[0], 'wall_time (s),sim_time (s),steps_per_second (1/s),dt (s),real_time_factor,'
        + 'fluid.kinetic_energy (J),max_density_deviation,max_speed (m/s),'
        + 'dfsph.density.last_residual,dfsph.density.max_iterations,dfsph.density.mean_iterations,'
        + 'dfsph.divergence.last_residual,dfsph.divergence.max_iterations,dfsph.divergence.mean_iterations');
      const now = await page.locator('#plots figcaption').allTextContents();
      assert.ok(now.some((c) => /^fluid\.kinetic energy \(J\): [\d.e+-]+$/.test(c)), now.join(' | '));
      assert.ok(lines.length >= 3, `only ${lines.length - 1} samples`);
      const sim = lines.slice(1).map((l) => Number(l.split(',')[1]));
      assert.ok(sim.every((v, i) => i === 0 || v > sim[i - 1]), `simulated time does not increase: ${sim}`);
      await shot(page, 'plots');
      await page.click('#plots .plots-close');
    });

    await t.test('record from the page, download the file, replay it with the timeline', async () => {
      await page.click('#record');
      await page.waitForFunction(() => Number(/(\d+) frames/.exec(document.querySelector('#record-status').textContent)?.[1]) >= 12,
        null, { timeout: 60_000 });
      await page.click('#record');
      const status = await text(page, '#record-status');
      const frames = Number(/^(\d+) frames/.exec(status)[1]);
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#record-status a')]);
      const bytes = await readFile(await download.path());
      assert.equal(bytes.subarray(0, 8).toString(), 'FLOEREC1');
      let count = 0;
      for (let at = 8; at < bytes.length; count++) at += 4 + bytes.readUInt32LE(at);
      assert.equal(count, frames, 'the file holds the frames the page says it recorded');

      await page.click('#record-status button');
      await page.waitForSelector('#timeline:not([hidden])');
      await page.waitForFunction((n) => document.querySelector('#tl-label').textContent.startsWith(`frame 1 / ${n},`), frames);
      await page.click('#tl-next');
      await page.waitForFunction(() => document.querySelector('#tl-label').textContent.startsWith('frame 2 /'));
      // Scrub to the end; play from there starts over and stops at the end by itself.
      await page.locator('#tl-slider').fill(String(frames - 1));
      await page.waitForFunction((n) => document.querySelector('#tl-label').textContent.startsWith(`frame ${n} /`), frames);
      await page.click('#tl-play');
      await page.waitForFunction((n) => document.querySelector('#tl-label').textContent.startsWith(`frame ${n} /`) &&
        document.querySelector('#tl-play').textContent === 'Play', frames, { timeout: 20_000 });
      // Pause holds the frame.
      await page.selectOption('#tl-speed', '0.001');
      await page.locator('#tl-slider').fill('0');
      await page.click('#tl-play');
      await page.waitForFunction(() => document.querySelector('#tl-play').textContent === 'Pause');
      await page.click('#tl-play');
      assert.equal(await text(page, '#tl-play'), 'Play');
      const paused = await text(page, '#tl-label');
      await page.waitForTimeout(600);
      assert.equal(await text(page, '#tl-label'), paused);
      assert.match(await text(page, '#stats'), /replay\s+dam_break-1\.rec/);
      assert.ok((await canvasSummary(page)).fluid > 1000, 'the replayed frame is drawn');
      await shot(page, 'replay');

      // A recording `floectl record` made: identity-ordered delta frames, keyframes at 0 and 30.
      await page.setInputFiles('#recording-file', path.join(root, 'web/test/data/dam_break_512.rec'));
      await page.waitForFunction(() => document.querySelector('#tl-label').textContent.startsWith('frame 1 / 40,'));
      await page.locator('#tl-slider').fill('35');
      await page.waitForFunction(() => document.querySelector('#tl-label').textContent.startsWith('frame 36 / 40, t = 0.759 s'));
      await page.keyboard.press('ArrowLeft');
      await page.waitForFunction(() => document.querySelector('#tl-label').textContent.startsWith('frame 35 / 40'));
      await settle(page);
      assert.equal(await stat(page, 'particles'), 512);

      // Not a recording: the error shows beside the control that opened it, and the live scene returns.
      await page.setInputFiles('#recording-file', { name: 'notes.rec', mimeType: 'application/octet-stream', buffer: Buffer.from('hello') });
      await page.waitForSelector('#replay-error:not([hidden])');
      assert.match(await text(page, '#replay-error'), /not a Floe recording \(no FLOEREC1 header\)/);
      await page.waitForSelector('#timeline', { state: 'hidden' });
      await statAtLeast(page, 'particles', 4096, 30_000);
      // The rest needs no motion: a paused scene leaves the page idle, so the test runs quicker.
      await page.click('#pause');
    });

    await t.test('the help overlay lists keys and mouse, "?" opens it and Escape closes it', async () => {
      await page.keyboard.press('?');
      await page.waitForSelector('#help:not([hidden])');
      const help = await text(page, '#help');
      for (const item of ['Space', 'run or pause', 'frame the scene', 'drag', 'zoom', 'pan']) assert.ok(help.includes(item), `help lacks "${item}"`);
      await shot(page, 'help');
      await page.keyboard.press('Escape');
      await page.waitForSelector('#help', { state: 'hidden' });
    });

    await t.test("the server's errors show beside the control used", async () => {
      await page.fill('#param', 'gravity=[0,oops]');
      await page.click('#apply');
      await page.waitForSelector('#param-error:not([hidden])');
      assert.match(await text(page, '#param-error'), /gravity/);
      const apply = await page.locator('#apply').boundingBox();
      const error = await page.locator('#param-error').boundingBox();
      assert.ok(error.y >= apply.y + apply.height && error.y - (apply.y + apply.height) < 30, 'the error is right under Apply');
      await page.click('#panel summary');
      await page.fill('#document', 'name = "broken"\nparticle_spacing = -1\n');
      await page.click('#create-doc');
      await page.waitForSelector('#create-doc-error:not([hidden])');
      assert.match(await text(page, '#create-doc-error'), /particle_spacing/);
      assert.equal(await page.isHidden('#create-error'), true, 'only the control used shows the error');
      // A good setting clears the error.
      await page.fill('#param', 'gravity=[0,-9.81,0]');
      await page.click('#apply');
      await page.waitForSelector('#param-error', { state: 'hidden' });
      await shot(page, 'error');
    });

    await t.test('at phone width the panel folds away and the view fills the screen', async () => {
      const phone = await browser.newPage({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true });
      const phoneProblems = watchProblems(phone);
      await phone.goto(url);
      await statAtLeast(phone, 'particles', 4096);
      await phone.waitForSelector('#panel', { state: 'hidden' });
      assert.equal(await phone.isVisible('#panel-toggle'), true);
      await settle(phone);
      const s = await canvasSummary(phone);
      assert.ok(s.fluid > 500, `only ${s.fluid} fluid pixels at phone width`);
      assert.ok(s.scene.x0 >= 0 && s.scene.x1 <= 390, 'the scene fits the width');
      await phone.click('#panel-toggle');
      const panel = await phone.locator('#panel').boundingBox();
      assert.ok(panel.x >= 0 && panel.x + panel.width <= 390, `the panel spans ${panel.x} to ${panel.x + panel.width}`);
      assert.ok(await phone.evaluate(() => document.documentElement.scrollWidth <= 390), 'the page scrolls sideways');
      await phone.screenshot({ path: path.join(root, 'target/viewer-phone.png') });
      assert.deepEqual(phoneProblems, []);
      await phone.close();
    });

    // The bad setting and scene file above answered 400, which the console reports too.
    const caused = (p) => p.startsWith('HTTP 400') || p.includes('status of 400');
    assert.deepEqual(problems.filter((p) => !caused(p)), [], 'no error but the ones the test caused');
  } finally {
    await browser.close();
    server.kill('SIGTERM');
  }
});
