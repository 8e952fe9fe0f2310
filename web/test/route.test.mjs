// The viewer follows a scene to its worker in a cluster: lists name it, 421 answers name it.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Routes, sceneOf } from '../js/route.js';

const answer = (status, body) => ({
  status,
  ok: status < 300,
  json: async () => body,
  clone() { return this; },
});

test('paths are about a scene, a new scene or neither', () => {
  assert.equal(sceneOf('/scenes/7/ws'), 7);
  assert.equal(sceneOf('/scenes/12'), 12);
  assert.equal(sceneOf('/scenes'), 'new');
  assert.equal(sceneOf('/presets'), null);
  assert.equal(sceneOf('/scenes/7x'), null);
});

test('a single server\'s paths stay as they are', async () => {
  const r = new Routes();
  r.learn([{ scene_id: 1, name: 'a' }]);
  assert.equal(r.url('/scenes/1/ws'), '/api/v1/scenes/1/ws');
  const asked = [];
  const res = await r.fetch(async (u) => { asked.push(u); return answer(200, {}); }, '/scenes/1');
  assert.equal(res.status, 200);
  assert.deepEqual(asked, ['/api/v1/scenes/1']);
});

test('lists and 421 answers route a scene through its worker', async () => {
  const r = new Routes();
  r.learn([{ scene_id: 3, worker: 'w2' }]);
  assert.equal(r.url('/scenes/3/ws'), '/w/w2/api/v1/scenes/3/ws');
  // The scene moved to w3: w2 names it, the call goes there, and stays there.
  const asked = [];
  const fetchFn = async (u) => {
    asked.push(u);
    return u.startsWith('/w/w3/') ? answer(200, { scene_id: 3 }) : answer(421, { error: 'on w3', worker: 'w3' });
  };
  assert.equal((await r.fetch(fetchFn, '/scenes/3/step', { method: 'POST' })).status, 200);
  assert.deepEqual(asked, ['/w/w2/api/v1/scenes/3/step', '/w/w3/api/v1/scenes/3/step']);
  assert.equal(r.url('/scenes/3'), '/w/w3/api/v1/scenes/3');
  // A new scene placed on w1 is remembered under its id; the next new scene is placed afresh.
  const created = await r.fetch(
    async (u) => (u === '/api/v1/scenes' ? answer(421, { worker: 'w1' }) : answer(201, { scene_id: 9 })),
    '/scenes',
    { method: 'POST' },
  );
  assert.equal(created.status, 201);
  assert.equal(r.url('/scenes/9/ws'), '/w/w1/api/v1/scenes/9/ws');
  assert.equal(r.url('/scenes'), '/api/v1/scenes');
  // No proxy in front (the same worker named over and over): the 421 is the answer.
  let calls = 0;
  const stuck = await r.fetch(async () => { calls += 1; return answer(421, { worker: 'w5' }); }, '/scenes/4');
  assert.equal(stuck.status, 421);
  assert.equal(calls, 4);
});
