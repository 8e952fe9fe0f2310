// The viewer through a cluster's proxy (tests/cluster.sh starts PostgreSQL, nginx and three
// workers on loopback and runs this with their addresses): a scene on each worker, each opened
// from the page the proxy served, streams its frames over a WebSocket through /w/WORKER/.
// Skipped without the cluster's addresses, unless FLOE_REQUIRE_CLUSTER=1.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { launchBrowser, statAtLeast, watchProblems } from './harness.mjs';

const proxy = process.env.FLOE_PROXY_HTTP;
const skip = !proxy && process.env.FLOE_REQUIRE_CLUSTER !== '1' && 'no cluster (tests/cluster.sh runs this)';

/** POSTs a new scene through the proxy, following a 421 to the worker it names. */
async function create(overrides) {
  const init = { method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify({ preset: 'dam_break', overrides }) };
  let r = await fetch(new URL('/api/v1/scenes', proxy), init);
  if (r.status === 421) r = await fetch(new URL(`/w/${(await r.json()).worker}/api/v1/scenes`, proxy), init);
  assert.equal(r.status, 201, await r.clone().text());
  return r.json();
}

test('each worker\'s scene streams to the viewer through the proxy', { skip, timeout: 180_000 }, async () => {
  assert.ok(proxy, 'FLOE_REQUIRE_CLUSTER is set but FLOE_PROXY_HTTP is not');
  const scenes = [];
  for (let k = 0; k < 3; k += 1) scenes.push(await create(['particle_spacing=0.05']));
  const workers = new Set(scenes.map((s) => s.worker));
  assert.equal(workers.size, 3, `one scene on each worker: ${JSON.stringify(scenes.map((s) => s.worker))}`);
  const browser = await launchBrowser();
  try {
    for (const scene of scenes) {
      const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
      const problems = watchProblems(page);
      await page.goto(new URL(`/#scene=${scene.scene_id}`, proxy).href);
      // The scene asked for, even where the worker that answered the list does not list it yet.
      await page.waitForFunction((id) => document.querySelector('#scenes').value === String(id), scene.scene_id,
        { timeout: 10_000 });
      await statAtLeast(page, 'frames', 1);
      // A 421 is a worker naming where the scene is: the page follows it (the browser still logs
      // the answer as a resource that failed to load).
      const misdirected = (p) => p.startsWith('HTTP 421') || p.includes('status of 421 (Misdirected Request)');
      assert.deepEqual(problems.filter((p) => !misdirected(p)), [], `scene on ${scene.worker}`);
      await page.close();
    }
  } finally {
    await browser.close();
    for (const s of scenes) await fetch(new URL(`/w/${s.worker}/api/v1/scenes/${s.scene_id}`, proxy), { method: 'DELETE' });
  }
});
