// Keys and mouse: one table drives both the key handling and the help overlay ('?').

/** Keys: `key` as in KeyboardEvent.key, the label shown, the action's name and what it does. */
export const KEYS = Object.freeze([
  { key: ' ', label: 'Space', action: 'playPause', does: 'run or pause the scene (in a replay: play or pause)' },
  { key: 's', label: 'S', action: 'step', does: 'one step of the scene' },
  { key: 'r', label: 'R', action: 'reset', does: 'back to t = 0' },
  { key: 'ArrowLeft', label: '←', action: 'previous', does: 'previous frame of a replay' },
  { key: 'ArrowRight', label: '→', action: 'next', does: 'next frame of a replay' },
  { key: '[', label: '[', action: 'slower', does: 'replay slower' },
  { key: ']', label: ']', action: 'faster', does: 'replay faster' },
  { key: 'v', label: 'V', action: 'view', does: 'surface or spheres' },
  { key: 'f', label: 'F', action: 'frame', does: 'frame the scene' },
  { key: 'p', label: 'P', action: 'plots', does: 'show or hide the plots' },
  { key: '?', label: '?', action: 'help', does: 'show or hide this help' },
  { key: 'Escape', label: 'Esc', action: 'dismiss', does: 'close this help' },
]);

/** Mouse and touch, for the help overlay. */
export const POINTER = Object.freeze([
  { label: 'drag', does: 'rotate about the scene' },
  { label: 'wheel, pinch', does: 'zoom' },
  { label: 'right-drag, shift-drag', does: 'pan' },
]);

/**
 * Whether a key press belongs to the focused control rather than the viewer: typing in a field,
 * choosing in a menu, arrows on a slider, Space or Enter on a button.
 */
function forControl(target, key) {
  const tag = target.tagName;
  if (tag === 'TEXTAREA' || tag === 'SELECT') return true;
  if (tag === 'BUTTON') return key === ' ' || key === 'Enter';
  if (tag !== 'INPUT') return false;
  if (target.type === 'range') return key.startsWith('Arrow');
  return !['checkbox', 'button', 'file'].includes(target.type);
}

/**
 * Calls `actions[name]()` for the keys of {@link KEYS} (not those a focused control takes, nor
 * with Ctrl, Alt or Meta).
 * @param {Object<string, () => void>} actions
 */
export function bindKeys(actions) {
  addEventListener('keydown', (e) => {
    if (forControl(e.target, e.key) || e.ctrlKey || e.altKey || e.metaKey) return;
    const row = KEYS.find((k) => k.key === e.key);
    if (!row || !actions[row.action]) return;
    e.preventDefault();
    actions[row.action]();
  });
}

/** Fills the help overlay `element` (its `dl`) from the tables. */
export function fillHelp(element) {
  const list = element.querySelector('dl');
  const row = (label, does) => {
    const dt = document.createElement('dt');
    dt.textContent = label;
    const dd = document.createElement('dd');
    dd.textContent = does;
    return [dt, dd];
  };
  list.replaceChildren(...KEYS.flatMap((k) => row(k.label, k.does)), ...POINTER.flatMap((p) => row(p.label, p.does)));
}
