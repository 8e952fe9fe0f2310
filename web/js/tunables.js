/**
 * Sliders for a scene's live settings, made from the tunables the server lists for it
 * (`{path, unit, min, max, about, module}`, see the scene's REST view): every tunable
 * holding one number with both bounds gets a slider, one per list entry for a path
 * through a list (`fluids[*].xsph` gives `fluids[0].xsph`, `fluids[1].xsph`, ...). A
 * module's settings thus appear without any change to the viewer.
 * @module
 */

/**
 * The value at `path` (`a.b[2].c`) in a scene document, or undefined.
 * @param {object} doc
 * @param {string} path
 */
export function valueAt(doc, path) {
  let node = doc;
  for (const key of path.replace(/\[(\d+)\]/g, '.$1').split('.')) {
    if (node === null || typeof node !== 'object') return undefined;
    node = node[key];
  }
  return node;
}

/**
 * The sliders for `tunables` in the scene document `doc`: one per bounded number whose current
 * value lies on the slider's 100 steps. A setting whose range is too wide for its value (a
 * viscosity clamp of 200 on 0 to 1e9 would snap to 0) gets no slider; the settings field takes it.
 * @param {{path: string, unit?: string, min?: number|null, max?: number|null, about?: string}[]} tunables
 * @param {object} doc the scene document (`scene.scene` in the REST view)
 * @returns {{path: string, unit: string, min: number, max: number, step: number, value: number, about: string}[]}
 */
export function sliders(tunables, doc) {
  const out = [];
  for (const t of tunables) {
    if (typeof t.min !== 'number' || typeof t.max !== 'number' || !(t.max > t.min)) continue;
    const [head, ...rest] = t.path.split('[*]');
    const paths = rest.length === 0 ? [head] : (valueAt(doc, head) ?? []).map((_, i) => `${head}[${i}]${rest.join('[*]')}`);
    for (const path of paths) {
      const value = valueAt(doc, path);
      if (typeof value !== 'number') continue;
      const step = (t.max - t.min) / 100;
      const k = (value - t.min) / step;
      if (Math.abs(k - Math.round(k)) > 1e-6 * Math.max(1, Math.abs(k))) continue;
      out.push({ path, unit: t.unit ?? '', min: t.min, max: t.max, step, value, about: t.about ?? '' });
    }
  }
  return out;
}
