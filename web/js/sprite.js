// The vertex shader every particle pass shares: a point sprite covering the particle's sphere,
// of radius u_radius, or u_radius times a_value where u_scaled (the surface view's lumps of
// hidden particles, cull.js; otherwise a_value is what the particle is coloured by).
//
// A sphere of radius r at view depth z spans r f / z in normalised device y (f = u_proj[1][1]),
// so its diameter in pixels is 2 (r f / z) (h / 2) = r f h / z for a viewport h pixels high:
// the point size. Fragment shaders rebuild the sphere from gl_PointCoord, with v_center (the
// particle's view-space position) to place its surface in depth.

import { ATTRIBUTES } from './gl.js';

export const SPRITE_VERT = `#version 300 es
uniform mat4 u_proj, u_view;
uniform float u_radius, u_viewport_h;
uniform bool u_scaled;
uniform vec2 u_range;
layout(location = ${ATTRIBUTES.position}) in vec3 a_pos;
layout(location = ${ATTRIBUTES.value}) in float a_value;
out float v_t, v_radius;
out vec3 v_center;
void main() {
  vec4 view = u_view * vec4(a_pos, 1.0);
  v_center = view.xyz;
  v_radius = u_scaled ? u_radius * a_value : u_radius;
  gl_Position = u_proj * view;
  gl_PointSize = max(1.0, v_radius * u_proj[1][1] * u_viewport_h / -view.z);
  // Every value the same (a fluid at rest coloured by speed): the middle of the colour map.
  float span = u_range.y - u_range.x;
  v_t = span > 0.0 ? clamp((a_value - u_range.x) / span, 0.0, 1.0) : 0.5;
}`;

/** GLSL: the window depth of a view-space point, for gl_FragDepth. */
export const WINDOW_DEPTH = `
float windowDepth(mat4 proj, vec3 p) {
  vec4 clip = proj * vec4(p, 1.0);
  return 0.5 * clip.z / clip.w + 0.5;
}`;

/** GLSL: the view-space point of the sprite's sphere under this fragment (and its normal), or discard. */
export const SPHERE_POINT = `${WINDOW_DEPTH}
vec3 spherePoint(vec3 center, float radius, out vec3 normal) {
  vec2 p = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(p, p);
  if (r2 > 1.0) discard;
  normal = vec3(p.x, -p.y, sqrt(1.0 - r2));
  return center + radius * normal;
}`;
