/**
 * Particles the sphere view need not draw: those deep inside the fluid. On software GL a frame's
 * cost grows with the particles drawn and the pixels they cover, and a body of water hides most
 * of its particles behind its outer ones.
 *
 * Space is cut into cubes of two particle spacings; a cube holding at least half the particles
 * it holds at rest (4) is full. A particle is left out when every cube within two of its own,
 * along each axis and diagonally (a 5 x 5 x 5 block), is full: then at least four spacings of
 * fluid lie between it and the outside in every direction. Through four spacings of fluid at
 * rest density a ray misses every sphere of physical size (spacing.js) less than 1 % of the
 * time, and one that gets through meets the spheres drawn on the far side, not the background:
 * the sphere view looks the same, bar a pixel's colour here and there. The surface view draws
 * every particle (its thickness counts them all).
 * @module
 */

/** Cube side, in particle spacings. */
const CELL = 2;
/** Particles in a full cube (half of CELL^3). */
const FULL = 4;
/** Full cubes needed on each side. */
const REACH = 2;
/** More cubes than this: no culling (a sparse or huge domain would cost more than it saves). */
const MAX_CELLS = 1 << 23;

/**
 * The particles to draw, in their order, and how many were left out.
 * @param {Float32Array} positions x, y, z interleaved (m)
 * @param {Float32Array|null} values one per particle, or null
 * @param {number} spacing particle spacing (m)
 * @param {{min: number[], max: number[]}} box the particles' bounding box (m)
 * @returns {{positions: Float32Array, values: Float32Array|null, hidden: number}}
 */
export function outerParticles(positions, values, spacing, box) {
  const n = positions.length / 3;
  const cell = CELL * spacing;
  // Cube faces half a spacing off the first particle: a lattice (a fluid at rest) never has
  // particles on a face, where rounding would split them unevenly between cubes.
  const origin = box.min.map((m) => m - spacing / 2);
  const dims = [0, 1, 2].map((k) => Math.floor((box.max[k] - origin[k]) / cell) + 1);
  const cells = dims[0] * dims[1] * dims[2];
  if (!(spacing > 0) || n === 0 || !(cells <= MAX_CELLS) || dims.some((d) => d <= 2 * REACH)) {
    return { positions, values, hidden: 0 };
  }
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
  let kept = 0;
  for (let i = 0; i < n; i++) if (!inner[index[i]]) kept += 1;
  if (kept === n) return { positions, values, hidden: 0 };
  const outP = new Float32Array(3 * kept), outV = values ? new Float32Array(kept) : null;
  for (let i = 0, j = 0; i < n; i++) {
    if (inner[index[i]]) continue;
    outP[3 * j] = positions[3 * i];
    outP[3 * j + 1] = positions[3 * i + 1];
    outP[3 * j + 2] = positions[3 * i + 2];
    if (outV) outV[j] = values[i];
    j += 1;
  }
  return { positions: outP, values: outV, hidden: n - kept };
}
