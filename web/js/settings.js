// The settings panel: the gravity slider and one slider per bounded numeric tunable of the
// scene shown (a module's settings included, tunables.js), each applied when released.

import { sliders } from './tunables.js';

const $ = (id) => document.getElementById(id);

export class SettingsPanel {
  /**
   * @param {(overrides: string[]) => unknown} apply changes the scene's settings
   *   (`path=value` overrides); its errors are the caller's to show
   */
  constructor(apply) {
    this.apply = apply;
    this.tunables = [];
    $('gravity').oninput = () => { $('gravity-value').textContent = Number($('gravity').value).toFixed(2); };
    $('gravity').onchange = () => apply([`gravity=[0,${$('gravity').value},0]`]);
  }

  /** Builds the sliders of a scene's REST view; the settings field's title lists every tunable with its unit. */
  show(scene) {
    this.tunables = scene.tunables ?? [];
    $('param').title = this.tunables.map((t) => `${t.path}${t.unit ? ` (${t.unit})` : ''}: ${t.about}`).join('\n');
    const rows = sliders(this.tunables, scene.scene ?? {}).flatMap((s) => {
      const label = document.createElement('label');
      const out = document.createElement('output');
      label.textContent = `${s.path} `;
      label.title = s.about;
      label.append(out, s.unit ? ` ${s.unit}` : '');
      const input = Object.assign(document.createElement('input'), { type: 'range', min: s.min, max: s.max, step: s.step });
      input.dataset.path = s.path;
      input.setAttribute('aria-label', s.path);
      label.htmlFor = input.id = `tunable-${s.path}`;
      input.oninput = () => { out.textContent = Number(input.value).toPrecision(3); };
      input.onchange = () => this.apply([`${s.path}=${input.value}`]);
      input.value = s.value;
      input.oninput();
      return [label, input];
    });
    $('tunables').replaceChildren(...rows);
  }

  /** Moves the sliders to a scene document's current settings (not one being dragged). */
  update(doc) {
    const g = doc?.gravity?.[1];
    if (typeof g === 'number' && document.activeElement !== $('gravity')) {
      $('gravity').value = g;
      $('gravity-value').textContent = g.toFixed(2);
    }
    for (const s of sliders(this.tunables, doc ?? {})) {
      const input = document.getElementById(`tunable-${s.path}`);
      if (input && document.activeElement !== input) {
        input.value = s.value;
        input.oninput();
      }
    }
  }
}
