/**
 * Particle size. A particle stands for a volume `h^3` of fluid (`h` the scene's particle
 * spacing); drawn as the sphere of that volume, radius `(3 / 4 pi)^(1/3) h`, a resting block
 * looks continuous from any side but along a lattice axis, and the spheres' volumes add up to
 * the fluid's, which the surface view's thickness pass relies on.
 * @module
 */

/** Radius of the sphere of volume `h^3`, over `h`. */
export const RADIUS_PER_SPACING = Math.cbrt(3 / (4 * Math.PI));

/** Drawing radius (m) of particles `spacing` (m) apart. */
export function physicalRadius(spacing) {
  return RADIUS_PER_SPACING * spacing;
}

/**
 * The particle spacing of a frame when the scene is not known (a replayed recording): the
 * median distance to the nearest neighbour of up to `samples` particles. SPH keeps neighbours
 * about one spacing apart, so this is the spacing within a few per cent; on a lattice it is
 * exact.
 * @param {Float32Array} positions x, y, z interleaved
 * @param {number} [samples]
 * @returns {number} metres; 0 for fewer than two particles
 */
export function estimateSpacing(positions, samples = 1000) {
  const n = positions.length / 3;
  if (n < 2) return 0;
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < 3 * n; i++) {
    const k = i % 3;
    if (positions[i] < min[k]) min[k] = positions[i];
    if (positions[i] > max[k]) max[k] = positions[i];
  }
  // Cells of about one spacing were the particles spread evenly over their bounding box; at
  // most 1024 a side (a flat set of particles gets larger cells, so more to search).
  const extent = [0, 1, 2].map((k) => max[k] - min[k]);
  const cell = Math.max(Math.cbrt(extent.reduce((p, e) => p * Math.max(e, 1e-9), 1) / n), Math.max(...extent) / 1024, 1e-9);
  const dims = extent.map((e) => Math.floor(e / cell) + 1);
  const key = (x, y, z) => (x * dims[1] + y) * dims[2] + z;
  const cellOf = (i, k) => Math.min(Math.floor((positions[3 * i + k] - min[k]) / cell), dims[k] - 1);
  const grid = new Map();
  for (let i = 0; i < n; i++) {
    const c = key(cellOf(i, 0), cellOf(i, 1), cellOf(i, 2));
    const list = grid.get(c);
    if (list) list.push(i);
    else grid.set(c, [i]);
  }
  const nearest = [];
  const stride = Math.max(1, Math.floor(n / samples));
  for (let i = 0; i < n; i += stride) {
    const c = [cellOf(i, 0), cellOf(i, 1), cellOf(i, 2)];
    let best = Infinity;
    for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
      const x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
      if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) continue;
      for (const j of grid.get(key(x, y, z)) ?? []) {
        if (j === i) continue;
        const d = Math.hypot(positions[3 * j] - positions[3 * i], positions[3 * j + 1] - positions[3 * i + 1],
          positions[3 * j + 2] - positions[3 * i + 2]);
        if (d > 0 && d < best) best = d;
      }
    }
    if (best < Infinity) nearest.push(best);
  }
  if (nearest.length === 0) return cell;
  nearest.sort((a, b) => a - b);
  return nearest[nearest.length >> 1];
}
