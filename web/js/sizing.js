/**
 * A preset the server sized for its machine. `floe serve --preset-size auto` starts a preset
 * created without a particle spacing at the finest spacing its backend steps at real time or
 * faster, and the scene says so (`SceneInfo.sizing`: the spacing and particles chosen, the
 * real-time factor measured there with the scene stepped alone, and the preset's own spacing and
 * particles). The page says what was chosen, and offers the full size: the same preset created
 * again at its own spacing.
 * @module
 */

/** A whole number with thousands separated, as "6,537". */
const count = (n) => n.toLocaleString('en-US');

/** A length (m) in centimetres, to three significant figures, as "1.75 cm" or "1 cm". */
const cm = (metres) => `${Number((100 * metres).toPrecision(3))} cm`;

/**
 * @typedef {object} Sizing
 * @property {number} spacing the particle spacing chosen (m)
 * @property {number} particles particles at it
 * @property {number} real_time_factor simulated over wall seconds measured at it, stepped alone
 * @property {number} full_spacing the preset's own spacing (m)
 * @property {number} full_particles particles at it
 */

/** Whether the server chose the preset's own spacing (a machine fast enough for it). */
function isFull(sizing) {
  return sizing.spacing === sizing.full_spacing;
}

/**
 * What the server chose, as "1,210 of 6,537 particles (1.75 cm spacing, full size 1 cm), sized
 * for this machine"; null for a scene it did not size (its creator gave the spacing, or the
 * server keeps every preset's own).
 * @param {Sizing|null|undefined} sizing the scene's `sizing`
 * @returns {string|null}
 */
export function sizingText(sizing) {
  if (!sizing) return null;
  const size = isFull(sizing)
    ? `${count(sizing.particles)} particles (${cm(sizing.spacing)} spacing, the full size)`
    : `${count(sizing.particles)} of ${count(sizing.full_particles)} particles (${cm(sizing.spacing)} spacing, full size ${cm(sizing.full_spacing)})`;
  return `${size}, sized for this machine`;
}

/**
 * The real-time factor the server measured when it sized the scene, stepped alone, beside the
 * one achieved: "; sized for 1.3"; empty for a scene it did not size.
 * @param {Sizing|null|undefined} sizing
 */
export function sizedRealTime(sizing) {
  return sizing ? `; sized for ${sizing.real_time_factor.toPrecision(2)}` : '';
}

/**
 * The body of `POST /api/v1/scenes` that creates a sized scene's preset at its full size: the
 * preset the scene is named after (only presets are sized) at its own spacing; or null when the
 * scene was not sized, or was sized at its full size already.
 * @param {{name: string, sizing?: Sizing}|null} scene the scene (`SceneInfo`)
 * @returns {{preset: string, overrides: string[]}|null}
 */
export function fullSizeRequest(scene) {
  const sizing = scene?.sizing;
  if (!sizing || isFull(sizing)) return null;
  return { preset: scene.name, overrides: [`particle_spacing=${sizing.full_spacing}`] };
}

/**
 * The Full size button's label: how many particles it asks for.
 * @param {Sizing} sizing
 */
export function fullSizeLabel(sizing) {
  return `Full size (${count(sizing.full_particles)} particles)`;
}
