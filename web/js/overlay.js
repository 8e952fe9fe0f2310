// The stats overlay's text: what is drawn, how fast, and the scene's (or the replay's) state.

import { sizedRealTime, sizingText } from './sizing.js';

/**
 * The real-time factor for the overlay: `achieved` (simulated over wall seconds, the last 3 s)
 * against `asked` (null: as fast as it goes), while `status` says the scene runs; slow below
 * 0.9 of what was asked.
 * @param {{state: string}|null} status @param {number} achieved @param {number|null} asked
 * @returns {{text: string, slow: boolean}}
 */
export function realTime(status, achieved, asked) {
  if (status?.state !== 'running') return { text: '', slow: false };
  if (!Number.isFinite(achieved)) return { text: 'measuring', slow: false };
  const slow = asked !== null && achieved < 0.9 * asked;
  const text = `${achieved.toPrecision(2)}${asked !== null ? ` of ${asked.toPrecision(2)} asked` : ''}${slow ? ' (cannot keep up)' : ''}`;
  return { text, slow };
}

/** The resolution of the frames drawn, where it is lowered while the picture moves (resolution.js). */
function resolutionNote(renderer) {
  const moving = renderer.resolution.moving;
  return moving < 1 ? ` at ${Math.round(100 * moving)} % resolution while moving` : '';
}

/**
 * The overlay's lines.
 * @param {object} o
 * @param {object} o.renderer the renderer (render.js)
 * @param {object|null} o.status the live scene's last status, null in a replay
 * @param {string[]|null} o.replay the replay's lines, null when live
 * @param {{text: string}} o.realTime from realTime()
 * @param {{renderFps: number, frames: number, skipped: number, lastBytes: number, decodeMs: number}} o.stream
 * @param {string[]} o.others the other particle sets' lines (sets.js)
 * @param {object|null} [o.sizing] the live scene's `sizing` (sizing.js), if the server sized it
 * @param {number|null} [o.inView] the scene's particles where frames carry the camera's view of
 *   them (view.js), null where they carry all
 */
export function statsText({ renderer, status: s, replay, realTime: rt, stream, others, sizing = null, inView = null }) {
  const sized = sizingText(sizing);
  return [
    stream.renderFps > 0 ? `render     ${stream.renderFps.toFixed(0)} fps (${renderer.view})${resolutionNote(renderer)}` : `render     idle (${renderer.view})`,
    `particles  ${renderer.count}${inView !== null ? ` of ${inView} (the camera's view)` : ''}${s ? ` on ${s.backend}` : ''}${renderer.drawnCount < renderer.count ? ` (${renderer.drawnCount} drawn)` : ''}`,
    sized ? `size       ${sized}` : '',
    renderer.oriented ? `oriented   ellipsoids ${renderer.radii.map((r) => (1000 * r).toPrecision(2)).join(' x ')} mm${renderer.view === 'spheres' ? '' : ' (spheres view)'}` : '',
    ...(replay ?? []),
    s ? `sim time   ${s.sim_time.toFixed(3)} s (${s.state})` : '',
    rt.text ? `real time  ${rt.text}${sizedRealTime(sizing)}` : '',
    s ? `steps/s    ${s.steps_per_second.toFixed(0)}` : '',
    replay ? '' : `frames     ${stream.frames}${stream.skipped ? ` (${stream.skipped} skipped, decoder busy)` : ''}`,
    replay ? '' : `bytes/frm  ${stream.lastBytes} (${(stream.lastBytes / Math.max(renderer.count, 1)).toFixed(2)} B/particle)`,
    `decode     ${stream.decodeMs.toFixed(2)} ms`,
    s ? `dropped    ${s.dropped_frames}` : '',
    ...(replay ? [] : others),
  ].filter(Boolean).join('\n');
}
