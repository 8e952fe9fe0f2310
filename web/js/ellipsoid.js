/**
 * Oriented particles drawn as ellipsoids. An elastic solid with `solid.oriented` on streams each
 * particle's rotation from rest as the channel `orientation` (a unit quaternion x, y, z, w); each
 * particle is then an ellipsoid of radii `solid.oriented.radii` (in particle spacings, default
 * 0.5 each) along its own axes, turned by that rotation. A sphere would hide the very thing the
 * solver tracks (how each particle turns), so the sphere view draws these ellipsoids instead.
 *
 * The sprite covers the ellipsoid's bounding sphere (its largest radius). The fragment shader
 * casts a ray along the view direction through the sprite (the orthographic approximation the
 * sphere impostor makes too) against the ellipsoid `p = c + M u`, `|u| = 1`, where `M` is the
 * view rotation times the particle's rotation times diag(radii): with `a = M^-1 d` (d the
 * fragment's offset in the sprite) and `b = M^-1 z`, `|a + t b| = 1` is a quadratic in t. The
 * normal, the gradient of `|M^-1 (p - c)|^2`, is `M^-T u`; M's rotation part is orthonormal, so
 * both inverses are cheap and no matrix is inverted per fragment.
 * @module
 */

import { ATTRIBUTES } from './gl.js';
import { NONE, findChannel } from './colour.js';
import { WINDOW_DEPTH } from './sprite.js';

/** The channel a scene streams orientations on. */
export const ORIENTATION = 'orientation';

/** Radii of an oriented particle (in particle spacings) when the scene does not give them. */
export const DEFAULT_RADII = Object.freeze([0.5, 0.5, 0.5]);

/**
 * The channels the page asks the particle stream for: the colour channel (none for `none`)
 * and, where the scene streams it, the orientation, so oriented particles are drawn turned
 * whatever they are coloured by.
 * @param {string} colour the colour mode (a channel name, or `'none'`)
 * @param {{name: string}[]} [sceneChannels] the channels the scene can stream
 * @returns {string[]} names, without repeats
 */
export function streamedChannels(colour, sceneChannels = []) {
  const names = colour && colour !== NONE ? [colour] : [];
  if (sceneChannels.some((c) => c.name === ORIENTATION) && !names.includes(ORIENTATION)) names.push(ORIENTATION);
  return names;
}

/**
 * The ellipsoid radii (m) of a scene's oriented particles, or null when they are off (the scene
 * document has no `solid.oriented`).
 * @param {object|null|undefined} doc the scene document (`SceneInfo.scene`)
 * @param {number} spacing the particle spacing (m)
 * @returns {number[]|null}
 */
export function orientedRadii(doc, spacing) {
  const oriented = doc?.solid?.oriented;
  if (!oriented) return null;
  const radii = Array.isArray(oriented.radii) && oriented.radii.length === 3 && oriented.radii.every((r) => r > 0)
    ? oriented.radii
    : DEFAULT_RADII;
  return radii.map((r) => r * spacing);
}

/**
 * A frame's orientations (4 values a particle, x, y, z, w), or null when it lacks them or they
 * do not match its particles.
 * @param {{positions: Float32Array, channels?: {name: string, tag?: number, components: number, values: ArrayLike<number>}[]}} frame
 * @param {{name: string, tag?: number}[]} [sceneChannels] the scene's channels, with their tags
 * @returns {Float32Array|null}
 */
export function orientationValues(frame, sceneChannels = []) {
  const found = findChannel(frame, ORIENTATION, sceneChannels);
  if (!found || found.components !== 4 || found.values.length !== (frame.positions.length / 3) * 4) return null;
  return found.values instanceof Float32Array ? found.values : Float32Array.from(found.values);
}

/**
 * The sprite's radius: the bounding sphere of the ellipsoid, whatever its rotation.
 * @param {number[]} radii the ellipsoid's radii (any unit)
 */
export function boundingRadius(radii) {
  return Math.max(...radii);
}

/**
 * The particle's own axes in world space: the columns of the rotation matrix of the quaternion
 * `q` = [x, y, z, w] (normalised first, as the shader does: the stream quantises it).
 * @param {ArrayLike<number>} q
 * @returns {number[][]} three unit vectors; the identity's for a zero quaternion
 */
export function quaternionAxes(q) {
  const len = Math.hypot(q[0], q[1], q[2], q[3]);
  if (!(len > 0)) return [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const [x, y, z, w] = [q[0] / len, q[1] / len, q[2] / len, q[3] / len];
  return [
    [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)],
    [2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)],
    [2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)],
  ];
}

/**
 * The ellipsoid program's vertex shader: as sprite.js's, plus the quaternion attribute, and
 * the particle's axes turned into view space for the fragment shader (flat: one vertex a sprite).
 */
export const ELLIPSOID_VERT = `#version 300 es
uniform mat4 u_proj, u_view;
uniform float u_radius, u_viewport_h;
uniform vec2 u_range;
layout(location = ${ATTRIBUTES.position}) in vec3 a_pos;
layout(location = ${ATTRIBUTES.value}) in float a_value;
layout(location = ${ATTRIBUTES.orientation}) in vec4 a_quat;
out float v_t;
out vec3 v_center;
flat out mat3 v_axes;
mat3 rotation(vec4 q) {
  float len = length(q);
  q = len > 0.0 ? q / len : vec4(0.0, 0.0, 0.0, 1.0);
  float x = q.x, y = q.y, z = q.z, w = q.w;
  return mat3(
    1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + z * w), 2.0 * (x * z - y * w),
    2.0 * (x * y - z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + x * w),
    2.0 * (x * z + y * w), 2.0 * (y * z - x * w), 1.0 - 2.0 * (x * x + y * y));
}
void main() {
  vec4 view = u_view * vec4(a_pos, 1.0);
  v_center = view.xyz;
  v_axes = mat3(u_view) * rotation(a_quat);
  gl_Position = u_proj * view;
  // u_radius: the largest radius, so the sprite covers the ellipsoid however it turns.
  gl_PointSize = max(1.0, u_radius * u_proj[1][1] * u_viewport_h / -view.z);
  float span = u_range.y - u_range.x;
  v_t = span > 0.0 ? clamp((a_value - u_range.x) / span, 0.0, 1.0) : 0.5;
}`;

/**
 * GLSL: the view-space point of the ellipsoid under this fragment and its normal, or discard.
 * Needs the uniforms u_radius (the sprite's) and u_radii (the ellipsoid's, m) and the
 * varyings v_center and v_axes.
 */
export const ELLIPSOID_POINT = `${WINDOW_DEPTH}
uniform float u_radius;
uniform vec3 u_radii;
in vec3 v_center;
flat in mat3 v_axes;
vec3 ellipsoidPoint(out vec3 normal) {
  vec2 s = gl_PointCoord * 2.0 - 1.0;
  if (dot(s, s) > 1.0) discard;
  vec3 d = vec3(s.x, -s.y, 0.0) * u_radius;
  // M^-1 = diag(1 / radii) v_axes^T (v_axes is orthonormal).
  mat3 toUnit = transpose(v_axes);
  vec3 a = (toUnit * d) / u_radii, b = (toUnit * vec3(0.0, 0.0, 1.0)) / u_radii;
  float bb = dot(b, b), ab = dot(a, b), disc = ab * ab - bb * (dot(a, a) - 1.0);
  if (disc < 0.0) discard;
  // The nearer of the two crossings: the larger view z (the camera looks along -z).
  float t = (-ab + sqrt(disc)) / bb;
  vec3 u = a + t * b;
  normal = normalize(v_axes * (u / u_radii));
  return v_center + d + vec3(0.0, 0.0, t);
}`;
