/**
 * Time series of a scene's statistics, for the plots panel and its CSV download.
 *
 * One series per entry of {@link STATS} (fields of the scene's status), the achieved real-time
 * factor (simulated over wall time between two samples), and one per entry of the status's
 * `measures` object (`{"<name>": {"value": v, "unit": "u"}}`), added as a scene first reports
 * it. Samples are taken against simulated time: a status is kept only when the scene has moved
 * on since the last one, and a step back in time (a reset, a restored snapshot) starts the
 * series afresh.
 * @module
 */

/** Statistics every scene reports, plotted in this order. */
export const STATS = Object.freeze([
  { name: 'steps_per_second', label: 'steps per second', unit: '1/s', of: (s) => s.steps_per_second },
  { name: 'dt', label: 'time step', unit: 's', of: (s) => s.dt },
]);

/** The derived series: simulated seconds per wall second between two samples, while running. */
export const REAL_TIME = Object.freeze({ name: 'real_time_factor', label: 'real-time factor (achieved)', unit: '' });

/**
 * Simulated over wall time between two statuses taken `wallSeconds` apart, or NaN when the scene
 * was not running at both (a pause, a manual step or a reset in between would mislead).
 * @param {{sim_time: number, state: string}} before @param {{sim_time: number, state: string}} after
 * @param {number} wallSeconds
 */
export function achievedRealTime(before, after, wallSeconds) {
  if (before.state !== 'running' || after.state !== 'running' || !(wallSeconds > 0)) return NaN;
  return (after.sim_time - before.sim_time) / wallSeconds;
}

/** The series of one scene. */
export class SeriesSet {
  /** @param {number} [capacity] samples kept; the oldest go first */
  constructor(capacity = 7200) {
    this.capacity = capacity;
    this.clear();
  }

  /** Forgets every sample and measure. */
  clear() {
    /** @type {{name: string, label: string, unit: string}[]} the plotted columns, in order */
    this.columns = [...STATS.map(({ name, label, unit }) => ({ name, label, unit })), { ...REAL_TIME }];
    /** Wall-clock seconds of each sample. */
    this.wall = [];
    /** Simulated time (s) of each sample. */
    this.sim = [];
    /** @type {Map<string, number[]>} each column's values, NaN where a sample lacks it */
    this.values = new Map(this.columns.map((c) => [c.name, []]));
    /** @type {{status: object, wall: number}|null} the last status seen, kept or not */
    this.last = null;
  }

  /** @returns {number} samples held */
  get length() {
    return this.sim.length;
  }

  /**
   * Takes a status (the scene's JSON) seen at `wall` seconds.
   * @param {{sim_time: number, state: string, measures?: Object<string, {value: number, unit?: string}>}} status
   * @param {number} wall a monotonic clock (s)
   * @returns {boolean} whether a sample was added
   */
  add(status, wall) {
    const last = this.last;
    this.last = { status, wall };
    if (typeof status?.sim_time !== 'number') return false;
    if (last !== null && status.sim_time < last.status.sim_time) {
      this.clear();
      this.last = { status, wall };
    }
    if (this.length > 0 && status.sim_time === this.sim[this.length - 1]) return false;
    const row = new Map(STATS.map((s) => [s.name, numberOr(s.of(status))]));
    row.set(REAL_TIME.name, last === null ? NaN : achievedRealTime(last.status, status, wall - last.wall));
    for (const [name, m] of Object.entries(status.measures ?? {})) {
      if (!this.values.has(name)) {
        this.columns.push({ name, label: name.replaceAll('_', ' '), unit: m?.unit ?? '' });
        this.values.set(name, new Array(this.length).fill(NaN));
      }
      row.set(name, numberOr(m?.value));
    }
    this.wall.push(wall);
    this.sim.push(status.sim_time);
    for (const [name, list] of this.values) list.push(row.get(name) ?? NaN);
    if (this.length > this.capacity) {
      this.wall.shift();
      this.sim.shift();
      for (const list of this.values.values()) list.shift();
    }
    return true;
  }

  /**
   * The achieved real-time factor over about the last `seconds` of wall time: simulated over
   * wall time from the earliest sample in that window the scene has been running since.
   * @param {number} seconds
   * @returns {number} NaN unless the last two samples were both taken running
   */
  recentRealTime(seconds) {
    const rtf = this.values.get(REAL_TIME.name);
    const last = this.length - 1;
    let first = last;
    while (first > 0 && Number.isFinite(rtf[first]) && this.wall[last] - this.wall[first - 1] <= seconds) first -= 1;
    if (first === last) return first > 0 && Number.isFinite(rtf[last]) ? rtf[last] : NaN;
    return (this.sim[last] - this.sim[first]) / (this.wall[last] - this.wall[first]);
  }

  /**
   * Every sample as CSV (RFC 4180): wall time from the first sample, simulated time, then one
   * column per series, headed `name (unit)`; an empty cell where a sample lacks a value.
   * @returns {string}
   */
  csv() {
    const head = ['wall_time (s)', 'sim_time (s)', ...this.columns.map((c) => (c.unit ? `${c.name} (${c.unit})` : c.name))];
    const lines = [head.map(csvField).join(',')];
    const t0 = this.wall[0] ?? 0;
    for (let i = 0; i < this.length; i++) {
      const cells = [this.wall[i] - t0, this.sim[i], ...this.columns.map((c) => this.values.get(c.name)[i])];
      lines.push(cells.map((v) => (Number.isFinite(v) ? String(v) : '')).join(','));
    }
    return `${lines.join('\r\n')}\r\n`;
  }
}

/** A finite number, else NaN. */
function numberOr(v) {
  return typeof v === 'number' && Number.isFinite(v) ? v : NaN;
}

/** A CSV field, quoted when it holds a comma, quote or line break. */
function csvField(text) {
  return /[",\r\n]/.test(text) ? `"${text.replaceAll('"', '""')}"` : text;
}
