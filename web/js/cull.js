/**
 * Fewer particles to draw where the fluid hides them. On software GL a frame's cost grows with
 * the particles drawn and the pixels they cover, and a body of water hides most of its
 * particles behind its outer ones.
 *
 * Space is cut into cubes of two particle spacings; a cube holding at least half the particles
 * it holds at rest (4) is full. A cube is inner when every cube within two of it, along each
 * axis and diagonally (a 5 x 5 x 5 block), is full: then at least four spacings of fluid lie
 * between its particles and the outside in every direction. Through four spacings of fluid at
 * rest density a ray misses every sphere of physical size (spacing.js) less than 1 % of the
 * time, and one that gets through meets the spheres drawn on the far side, not the background.
 *
 * - The sphere view leaves inner cubes' particles out ({@link outerParticles}): it looks the
 *   same, bar a pixel's colour here and there.
 * - The surface view draws each inner cube as one sphere of its particles' volume at their mean
 *   position ({@link lumpedParticles}): hidden as they are, they change no depth, and the water's
 *   thickness keeps its volume.
 * - Seen from afar, where a spacing covers a pixel or two of the surface passes, the surface view
 *   draws every cube so, outer ones too ({@link cubeLumps}): a lump then spans a few pixels, which
 *   the passes' smoothing irons out as it does single particles' bumps, and a quarter as many
 *   points or fewer are drawn.
 * @module
 */

/** Cube side, in particle spacings. */
export const CELL = 2;
/** Particles in a full cube (half of CELL^3). */
const FULL = 4;
/** Full cubes needed on each side. */
const REACH = 2;
/** More cubes than this: no culling (a sparse or huge domain would cost more than it saves). */
const MAX_CELLS = 1 << 23;

/**
 * Each particle's cube, and the particles in each cube (at most 255 counted), or null without
 * particles, without a spacing or for more than MAX_CELLS cubes.
 * @param {Float32Array} positions x, y, z interleaved (m)
 * @param {number} spacing particle spacing (m)
 * @param {{min: number[], max: number[]}} box the particles' bounding box (m)
 * @returns {{index: Uint32Array, count: Uint8Array, dims: number[]}|null}
 */
export function cubesOf(positions, spacing, box) {
  const n = positions.length / 3;
  const cell = CELL * spacing;
  // Cube faces half a spacing off the first particle: a lattice (a fluid at rest) never has
  // particles on a face, where rounding would split them unevenly between cubes.
  const origin = box.min.map((m) => m - spacing / 2);
  const dims = [0, 1, 2].map((k) => Math.floor((box.max[k] - origin[k]) / cell) + 1);
  const cells = dims[0] * dims[1] * dims[2];
  if (!(spacing > 0) || n === 0 || !(cells <= MAX_CELLS)) return null;
  const index = new Uint32Array(n);
  const count = new Uint8Array(cells);
  for (let i = 0; i < n; i++) {
    let c = 0;
    for (let k = 0; k < 3; k++) {
      const q = Math.min(Math.floor((positions[3 * i + k] - origin[k]) / cell), dims[k] - 1);
      c = c * dims[k] + q;
    }
    index[i] = c;
    if (count[c] < 255) count[c] += 1;
  }
  return { index, count, dims };
}

/**
 * Each particle's cube and which cubes are inner, or null when none is.
 * @param {Float32Array} positions x, y, z interleaved (m)
 * @param {number} spacing particle spacing (m)
 * @param {{min: number[], max: number[]}} box the particles' bounding box (m)
 * @param {ReturnType<typeof cubesOf>} [grid] the particles' cubes, when made already
 * @returns {{index: Uint32Array, inner: Uint8Array, count: Uint8Array, hidden: number}|null}
 *   `hidden`: particles in inner cubes
 */
export function innerCubes(positions, spacing, box, grid = cubesOf(positions, spacing, box)) {
  if (!grid || grid.dims.some((d) => d <= 2 * REACH)) return null;
  const { index, count, dims } = grid;
  const n = index.length, cells = count.length;
  let inner = count.map((m) => (m >= FULL ? 1 : 0));
  // Erode along each axis in turn: a cube stays when every cube within REACH along that axis is
  // full (outside the grid counts as empty); three passes erode by the 5 x 5 x 5 block.
  const strides = [dims[1] * dims[2], dims[2], 1];
  for (let axis = 0; axis < 3; axis++) {
    const next = new Uint8Array(cells);
    const stride = strides[axis], size = dims[axis];
    for (let c = 0; c < cells; c++) {
      if (!inner[c]) continue;
      const q = Math.floor(c / stride) % size;
      if (q < REACH || q >= size - REACH) continue;
      let all = 1;
      for (let d = -REACH; d <= REACH && all; d++) all = inner[c + d * stride];
      next[c] = all;
    }
    inner = next;
  }
  let hidden = 0;
  for (let i = 0; i < n; i++) hidden += inner[index[i]];
  return hidden === 0 ? null : { index, inner, count, hidden };
}

/**
 * The particles outside inner cubes, in their order, with their values.
 * @param {Float32Array} positions @param {Float32Array|null} values
 * @param {ReturnType<typeof innerCubes>} cubes
 * @returns {{positions: Float32Array, values: Float32Array|null}}
 */
export function outerParticles(positions, values, cubes) {
  if (!cubes) return { positions, values };
  const n = positions.length / 3, kept = n - cubes.hidden;
  const outP = new Float32Array(3 * kept), outV = values ? new Float32Array(kept) : null;
  for (let i = 0, j = 0; i < n; i++) {
    if (cubes.inner[cubes.index[i]]) continue;
    outP[3 * j] = positions[3 * i];
    outP[3 * j + 1] = positions[3 * i + 1];
    outP[3 * j + 2] = positions[3 * i + 2];
    if (outV) outV[j] = values[i];
    j += 1;
  }
  return { positions: outP, values: outV };
}

/**
 * The particles outside inner cubes, then one per inner cube at its particles' mean position;
 * `scales` gives each one's radius over a particle's (1 for a particle, the cube root of the
 * particles merged for a cube, so its volume is theirs).
 * @param {Float32Array} positions
 * @param {ReturnType<typeof innerCubes>} cubes
 * @returns {{positions: Float32Array, scales: Float32Array}}
 */
export function lumpedParticles(positions, cubes) {
  const n = positions.length / 3;
  if (!cubes) return { positions, scales: new Float32Array(n).fill(1) };
  const kept = n - cubes.hidden;
  const lumps = lumpsOf(positions, cubes.index, cubes.inner.length, (c) => cubes.inner[c]);
  const m = lumps.scales.length;
  const outP = new Float32Array(3 * (kept + m)), scales = new Float32Array(kept + m).fill(1);
  outP.set(outerParticles(positions, null, cubes).positions);
  outP.set(lumps.positions, 3 * kept);
  scales.set(lumps.scales, kept);
  return { positions: outP, scales };
}

/**
 * One sphere per cube that holds particles, of their volume at their mean position (scales as
 * {@link lumpedParticles} gives them); the particles themselves without a grid.
 * @param {Float32Array} positions
 * @param {ReturnType<typeof cubesOf>} grid
 * @returns {{positions: Float32Array, scales: Float32Array}}
 */
export function cubeLumps(positions, grid) {
  if (!grid) return { positions, scales: new Float32Array(positions.length / 3).fill(1) };
  return lumpsOf(positions, grid.index, grid.count.length, () => true);
}

/** The lumps of the cubes `merge` picks, numbered in the order their first particle is met. */
function lumpsOf(positions, index, cells, merge) {
  const n = index.length;
  const slot = new Int32Array(cells).fill(-1);
  let lumps = 0;
  for (let i = 0; i < n; i++) {
    const c = index[i];
    if (slot[c] < 0 && merge(c)) slot[c] = lumps++;
  }
  const sums = new Float64Array(4 * lumps);
  for (let i = 0; i < n; i++) {
    const s = slot[index[i]];
    if (s < 0) continue;
    sums[4 * s] += positions[3 * i];
    sums[4 * s + 1] += positions[3 * i + 1];
    sums[4 * s + 2] += positions[3 * i + 2];
    sums[4 * s + 3] += 1;
  }
  const out = new Float32Array(3 * lumps), scales = new Float32Array(lumps);
  for (let s = 0; s < lumps; s++) {
    const m = sums[4 * s + 3];
    out[3 * s] = sums[4 * s] / m;
    out[3 * s + 1] = sums[4 * s + 1] / m;
    out[3 * s + 2] = sums[4 * s + 2] / m;
    scales[s] = Math.cbrt(m);
  }
  return { positions: out, scales };
}
