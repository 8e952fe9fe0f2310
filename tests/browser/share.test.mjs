// A scene shown in a notebook (`Client.show` in the Python client) is the viewer at
// `<viewer>/#scene=<id>&token=<share token>`, the address the REST API's share call gives: opened
// there, the viewer draws the scene's frames as it runs, and its controls cannot steer the scene
// (the share link only watches).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { canvasSummary, floeBinary, launchBrowser, startServer, statAtLeast, tempDataDir, watchProblems } from './harness.mjs';

test('the viewer on a share link draws the scene and cannot steer it', { timeout: 120_000 }, async () => {
  const dataDir = tempDataDir();
  const added = execFileSync(floeBinary(), ['admin', '--data-dir', dataDir, 'user', 'add', 'ada']).toString();
  const owner = { authorization: `Bearer ${added.match(/floe_pat_\w+/)[0]}`, 'content-type': 'application/json' };
  const { child, url } = await startServer({ dataDir });
  const api = (path, init = {}) => fetch(new URL(`/api/v1${path}`, url), { headers: owner, ...init });
  const browser = await launchBrowser();
  try {
    const created = await api('/scenes', { method: 'POST', body: JSON.stringify({ preset: 'dam_break', overrides: ['particle_spacing=0.05'] }) });
    assert.equal(created.status, 201, await created.clone().text());
    const id = (await created.json()).scene_id;
    const share = await (await api(`/scenes/${id}/shares`, { method: 'POST' })).json();
    assert.equal(share.viewer, `/#scene=${id}&token=${share.token}`);

    const page = await browser.newPage({ viewport: { width: 900, height: 600 } });
    const problems = watchProblems(page);
    await page.goto(new URL(share.viewer, url).href);
    await statAtLeast(page, 'particles', 1000);
    // The owner runs the scene; the shared viewer follows it.
    assert.equal((await api(`/scenes/${id}/run`, { method: 'POST', body: '{}' })).status, 200);
    await statAtLeast(page, 'frames', 10);
    const drawn = await canvasSummary(page);
    assert.ok(drawn.fluid > 2000, `only ${drawn.fluid} pixels of water drawn`);
    await api(`/scenes/${id}/pause`, { method: 'POST', body: '{}' });

    // Its play button asks the server to run the scene, which refuses the share link.
    const steps = (await (await api(`/scenes/${id}`)).json()).steps;
    await page.click('#play');
    await page.waitForSelector('#controls-error:not([hidden])', { timeout: 10_000 });
    assert.match(await page.textContent('#controls-error'), /./);
    const after = await (await api(`/scenes/${id}`)).json();
    assert.equal(after.state, 'paused');
    assert.equal(after.steps, steps);
    // The refused run, as the browser reports it (a console line and the response).
    assert.ok(problems.length > 0 && problems.every((p) => /\b403\b/.test(p)), problems.join('\n'));
  } finally {
    await browser.close();
    child.kill();
    await child.exited;
  }
});
