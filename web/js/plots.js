// The plots panel: one small line plot per series of the scene's statistics (series.js) against
// simulated time, the unit on each axis, the latest value in the caption, and a CSV download of
// everything plotted.

import { SeriesSet } from './series.js';

const HEIGHT = 64;
const MARGIN = { left: 46, right: 6, top: 6, bottom: 16 };

/** A number in at most 3 significant digits, exponent form when very small or large. */
export function formatValue(v) {
  if (!Number.isFinite(v)) return '–';
  const a = Math.abs(v);
  return a !== 0 && (a < 1e-3 || a >= 1e5) ? v.toExponential(2) : String(Number(v.toPrecision(3)));
}

/** The plots panel in `element` (with `.plot-list`, `.plots-csv` and `.plots-close`). */
export class PlotPanel {
  constructor(element) {
    this.element = element;
    this.list = element.querySelector('.plot-list');
    this.series = new SeriesSet();
    /** Name for the CSV file. */
    this.name = 'scene';
    element.querySelector('.plots-csv').onclick = () => this.download();
    element.querySelector('.plots-close').onclick = () => this.toggle(false);
  }

  /** Whether the panel is shown. */
  get visible() {
    return !this.element.hidden;
  }

  /** Shows or hides the panel (toggles without an argument). */
  toggle(show = !this.visible) {
    this.element.hidden = !show;
    if (show) this.draw();
  }

  /** A new scene (or none): forget the series. */
  reset(name) {
    this.series.clear();
    this.name = name;
    if (this.visible) this.draw();
  }

  /** Takes a status seen at `wall` seconds; redraws when it made a sample. */
  add(status, wall) {
    if (this.series.add(status, wall) && this.visible) this.draw();
  }

  /** Offers the CSV of every series as a download. */
  download() {
    const url = URL.createObjectURL(new Blob([this.series.csv()], { type: 'text/csv' }));
    const a = document.createElement('a');
    a.href = url;
    a.download = `floe-${this.name}-stats.csv`;
    a.click();
    setTimeout(() => URL.revokeObjectURL(url), 10_000);
  }

  /** Redraws every plot, adding figures for new series. */
  draw() {
    const s = this.series;
    while (this.list.children.length < s.columns.length) {
      const figure = document.createElement('figure');
      figure.append(document.createElement('figcaption'), document.createElement('canvas'));
      this.list.append(figure);
    }
    while (this.list.children.length > s.columns.length) this.list.lastChild.remove();
    s.columns.forEach((column, i) => {
      const figure = this.list.children[i];
      const values = s.values.get(column.name);
      figure.dataset.series = column.name;
      figure.querySelector('figcaption').textContent =
        `${column.label}${column.unit ? ` (${column.unit})` : ''}: ${formatValue(values.at(-1))}`;
      plot(figure.querySelector('canvas'), s.sim, values, column.unit);
    });
  }
}

/** Draws one series against simulated time. */
function plot(canvas, times, values, unit) {
  const dpr = devicePixelRatio || 1;
  const cssWidth = canvas.clientWidth || 260;
  canvas.width = Math.round(cssWidth * dpr);
  canvas.height = Math.round(HEIGHT * dpr);
  const g = canvas.getContext('2d');
  g.scale(dpr, dpr);
  g.clearRect(0, 0, cssWidth, HEIGHT);
  const w = cssWidth - MARGIN.left - MARGIN.right, h = HEIGHT - MARGIN.top - MARGIN.bottom;
  let lo = Infinity, hi = -Infinity;
  for (const v of values) if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  g.strokeStyle = '#3a4854';
  g.strokeRect(MARGIN.left + 0.5, MARGIN.top + 0.5, w, h);
  g.fillStyle = '#9fb0c0';
  g.font = '10px system-ui, sans-serif';
  if (!(lo <= hi) || times.length === 0) {
    g.fillText('no samples yet', MARGIN.left + 6, MARGIN.top + h / 2 + 3);
    return;
  }
  if (hi === lo) { hi += Math.abs(hi) * 0.05 || 1; lo -= Math.abs(lo) * 0.05 || 1; }
  const t0 = times[0], t1 = Math.max(times[times.length - 1], t0 + 1e-9);
  const x = (t) => MARGIN.left + ((t - t0) / (t1 - t0)) * w;
  const y = (v) => MARGIN.top + (1 - (v - lo) / (hi - lo)) * h;
  g.textAlign = 'right';
  g.fillText(formatValue(hi), MARGIN.left - 4, MARGIN.top + 8);
  g.fillText(formatValue(lo), MARGIN.left - 4, MARGIN.top + h);
  if (unit) g.fillText(unit, MARGIN.left - 4, MARGIN.top + h / 2 + 3);
  g.textAlign = 'left';
  g.fillText(`${formatValue(t0)} s`, MARGIN.left, HEIGHT - 3);
  g.textAlign = 'right';
  g.fillText(`sim time ${formatValue(t1)} s`, MARGIN.left + w, HEIGHT - 3);
  g.strokeStyle = '#5fb0e8';
  g.lineWidth = 1.5;
  g.beginPath();
  let pen = false;
  for (let i = 0; i < values.length; i++) {
    if (!Number.isFinite(values[i])) { pen = false; continue; }
    if (pen) g.lineTo(x(times[i]), y(values[i]));
    else g.moveTo(x(times[i]), y(values[i]));
    pen = true;
  }
  g.stroke();
  if (values.filter(Number.isFinite).length === 1) {
    const i = values.findIndex(Number.isFinite);
    g.fillStyle = '#5fb0e8';
    g.fillRect(x(times[i]) - 1.5, y(values[i]) - 1.5, 3, 3);
  }
}
