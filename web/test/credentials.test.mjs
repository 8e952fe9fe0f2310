// The viewer's credential: read once from the fragment, kept, sent on REST and WebSocket.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { Credentials } from '../js/credentials.js';

function storage() {
  const m = new Map();
  return { getItem: (k) => m.get(k) ?? null, setItem: (k, v) => m.set(k, v) };
}

test('a token and scene in the fragment are taken once and cleared from the address', () => {
  const c = new Credentials(storage());
  const replaced = [];
  const history = { replaceState: (_s, _t, url) => replaced.push(url) };
  assert.deepEqual(c.headers(), {});
  assert.deepEqual(c.protocols(), ['floe.v1']);
  const scene = c.readFragment({ hash: '#scene=3&token=floe_shr_abc', pathname: '/', search: '' }, history);
  assert.equal(scene, 3);
  assert.deepEqual(replaced, ['/']);
  assert.deepEqual(c.headers(), { authorization: 'Bearer floe_shr_abc' });
  assert.deepEqual(c.protocols(), ['floe.v1', 'floe_shr_abc']);
  // A later address without a fragment keeps the token and changes nothing.
  assert.equal(c.readFragment({ hash: '', pathname: '/', search: '' }, history), undefined);
  assert.equal(replaced.length, 1);
  assert.equal(c.readFragment({ hash: '#scene=x', pathname: '/', search: '' }, history), undefined);
});
