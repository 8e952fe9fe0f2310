// The Web Worker entry (web/js/codec/worker.js), run in a Node worker thread with `self`
// mapped onto the thread's port. Run: node --test web/test/
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import { Worker } from 'node:worker_threads';
import { Decoder } from '../js/codec/index.js';

const DATA = new URL('../../proto/testdata/', import.meta.url);
const bin = (name) => new Uint8Array(readFileSync(new URL(`${name}.bin`, DATA)));
const WORKER = new URL('../js/codec/worker.js', import.meta.url).href;

/** Starts worker.js as a browser would see it: a global `self` with `postMessage` and `onmessage`. */
function start() {
  const shim = `
    const { parentPort } = require('node:worker_threads');
    globalThis.self = { postMessage: (message, transfer) => parentPort.postMessage(message, transfer) };
    import(${JSON.stringify(WORKER)}).then(() => parentPort.on('message', (data) => self.onmessage({ data })));
  `;
  const worker = new Worker(shim, { eval: true });
  const replies = [];
  const waiting = [];
  worker.on('message', (m) => (waiting.length ? waiting.shift()(m) : replies.push(m)));
  const ask = (message, transfer = []) => {
    worker.postMessage(message, transfer);
    return replies.length ? Promise.resolve(replies.shift()) : new Promise((resolve) => waiting.push(resolve));
  };
  return { worker, ask };
}

test('the worker decodes a stream with one decoder and transfers the arrays back', async () => {
  const { worker, ask } = start();
  try {
    const direct = new Decoder();
    for (const [i, name] of ['identity_keyframe', 'identity_delta', 'identity_linear', 'unordered_channels'].entries()) {
      const bytes = bin(name);
      const want = direct.decode(bytes);
      const buffer = bytes.slice().buffer;
      const reply = await ask({ id: i, bytes: buffer }, [buffer]);
      assert.equal(buffer.byteLength, 0, 'the input buffer was transferred');
      assert.equal(reply.id, i);
      assert.equal(reply.error, undefined, JSON.stringify(reply.error));
      assert.equal(typeof reply.decodeMs, 'number');
      assert.ok(reply.decodeMs >= 0);
      assert.equal(reply.header.sequence, want.header.sequence);
      assert.equal(typeof reply.header.sceneId, 'bigint');
      assert.deepEqual(reply.positions, want.positions, `${name}: positions`);
      assert.deepEqual(reply.channels, want.channels, `${name}: channels`);
    }
  } finally {
    await worker.terminate();
  }
});

test('the worker reports decode errors by kind, and takes limits and resets', async () => {
  const { worker, ask } = start();
  try {
    let reply = await ask({ id: 'a', bytes: bin('identity_delta').buffer });
    assert.equal(reply.id, 'a');
    assert.equal(reply.error.kind, 'NeedKeyframe');
    assert.equal(reply.error.base, 0n);
    assert.match(reply.error.message, /keyframe is needed/);
    reply = await ask({ bytes: new Uint8Array([1, 2, 3]).buffer });
    assert.equal(reply.error.kind, 'Malformed');
    const whole = bin('unordered_positions');
    reply = await ask({ bytes: whole.subarray(0, 100).slice().buffer });
    assert.deepEqual([reply.error.kind, reply.error.needed, reply.error.available], ['Incomplete', whole.length, 100]);
    reply = await ask({ nothing: true });
    assert.equal(reply.error.kind, 'TypeError');
    assert.deepEqual(await ask({ id: 1, limits: { maxParticles: 10 } }), { id: 1, ok: true });
    reply = await ask({ bytes: bin('unordered_positions').buffer });
    assert.deepEqual([reply.error.kind, reply.error.what, reply.error.declared, reply.error.limit], ['TooLarge', 'particles', 200, 10]);
    assert.deepEqual(await ask({ limits: {} }), { id: undefined, ok: true });
    assert.equal((await ask({ bytes: bin('identity_keyframe').buffer })).header.sequence, 0n);
    assert.deepEqual(await ask({ reset: true }), { id: undefined, ok: true });
    assert.equal((await ask({ bytes: bin('identity_delta').buffer })).error.kind, 'NeedKeyframe');
  } finally {
    await worker.terminate();
  }
});
