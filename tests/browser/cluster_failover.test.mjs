// The viewer following its scene across a worker's death (tests/cluster.sh runs this last,
// after the Rust client's test has killed floe-2): a scene on floe-3 streams to the page through
// the proxy; floe-3 is killed (kill -9); the scene comes back, paused, on floe-1, and the page,
// left alone, finds it there and shows the steps taken on its new worker.
// Skipped without the cluster's addresses, unless FLOE_REQUIRE_CLUSTER=1.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { launchBrowser, stat, statAtLeast, watchProblems } from './harness.mjs';

const proxy = process.env.FLOE_PROXY_HTTP;
const skip = !proxy && process.env.FLOE_REQUIRE_CLUSTER !== '1' && 'no cluster (tests/cluster.sh runs this)';

/** A JSON call through the proxy to `/w/WORKER/api/v1/PATH`, or to any worker without one. */
async function call(worker, path, method = 'GET', body = undefined) {
  const prefix = worker ? `/w/${worker}` : '';
  const init = body ? { method, headers: { 'content-type': 'application/json' }, body: JSON.stringify(body) } : { method };
  return fetch(new URL(`${prefix}/api/v1/${path}`, proxy), init);
}

test('the viewer follows its scene when its worker is killed', { skip, timeout: 180_000 }, async () => {
  assert.ok(proxy, 'FLOE_REQUIRE_CLUSTER is set but FLOE_PROXY_HTTP is not');
  const created = await call('floe-3', 'scenes', 'POST', { preset: 'dam_break', overrides: ['particle_spacing=0.05'] });
  assert.equal(created.status, 201, await created.clone().text());
  const scene = await created.json();
  assert.equal(scene.worker, 'floe-3');
  const stepped = await call('floe-3', `scenes/${scene.scene_id}/step`, 'POST', { steps: 3 });
  assert.equal(stepped.status, 200, await stepped.clone().text());
  const browser = await launchBrowser();
  try {
    const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
    const problems = watchProblems(page);
    // Opened at once: a worker that does not list the new scene yet (it does after its next
    // tick) leaves the page to ask for it by id.
    await page.goto(new URL(`/#scene=${scene.scene_id}`, proxy).href);
    await page.waitForFunction((id) => document.querySelector('#scenes').value === String(id), scene.scene_id,
      { timeout: 10_000 });
    await statAtLeast(page, 'frames', 1);
    const framesBefore = await stat(page, 'frames');

    assert.ok(process.kill(Number(process.env.FLOE_CLUSTER_WORKER_3_PID), 'SIGKILL'));
    let now = 'floe-3';
    const t0 = Date.now();
    while (now === 'floe-3') {
      assert.ok(Date.now() - t0 < 30_000, `scene ${scene.scene_id} still on floe-3 after 30 s`);
      await new Promise((done) => setTimeout(done, 250));
      const list = await call(null, 'scenes');
      // While the scene moves the list may leave it out or name no worker for it.
      if (list.ok) now = (await list.json()).find((s) => s.scene_id === scene.scene_id)?.worker || 'floe-3';
    }
    assert.equal(now, 'floe-1', 'floe-2 is gone (the Rust test killed it): floe-1 takes the scene');
    const on = await call(now, `scenes/${scene.scene_id}/step`, 'POST', { steps: 20 });
    assert.equal(on.status, 200, await on.clone().text());
    const info = await on.json();
    assert.equal(info.worker, 'floe-1');
    // The page, left alone, reconnects to the scene's new worker and shows what it steps.
    await page.waitForFunction((t) => {
      const m = /sim time\s+([\d.]+) s/.exec(document.querySelector('#stats').textContent);
      return m && Number(m[1]) >= t;
    }, Number(info.sim_time.toFixed(3)), { timeout: 60_000 });
    assert.ok(await stat(page, 'frames') > framesBefore, 'frames from the new worker');
    // While floe-3 was dead, its reconnects failed or were told where the scene is; nothing
    // else went wrong on the page.
    assert.deepEqual(problems.filter((p) => p.startsWith('page error')), []);
  } finally {
    await browser.close();
    const list = await call(null, 'scenes');
    const where = list.ok ? (await list.json()).find((s) => s.scene_id === scene.scene_id)?.worker : undefined;
    if (where) await call(where, `scenes/${scene.scene_id}`, 'DELETE');
  }
});
