// The scene's terrains (`GET /api/v1/scenes/{id}/terrain`): each height grid drawn as a mesh of
// two triangles per grid cell, lit by one directional light (Lambert, with an ambient term), under
// the particles.

import { programWith } from './gl.js';

const VERT = `#version 300 es
uniform mat4 u_proj, u_view;
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
out vec3 v_normal;
void main() {
  v_normal = a_normal;
  gl_Position = u_proj * u_view * vec4(a_pos, 1.0);
}`;

const FRAG = `#version 300 es
precision highp float;
in vec3 v_normal;
out vec4 colour;
void main() {
  // The light comes from above, a little from +z and -x: slopes facing it are brighter.
  vec3 l = normalize(vec3(-0.4, 0.8, 0.45));
  float diffuse = max(dot(normalize(v_normal), l), 0.0);
  colour = vec4(vec3(0.55, 0.5, 0.44) * (0.3 + 0.7 * diffuse), 1.0);
}`;

/**
 * Vertices (x, y, z), unit normals and triangle indices of a terrain's grid: node (i, k) at
 * `min + (i, k) (max - min) / (n - 1)` with height `heights[k nx + i]`; normals from central
 * differences (one-sided at the edges), as the server's bilinear normal is at a node.
 * @param {{min: number[], max: number[], nx: number, nz: number, heights: number[]}} t
 */
export function terrainMesh(t) {
  const { min, max, nx, nz, heights } = t;
  const dx = (max[0] - min[0]) / (nx - 1), dz = (max[1] - min[1]) / (nz - 1);
  const h = (i, k) => heights[Math.min(Math.max(k, 0), nz - 1) * nx + Math.min(Math.max(i, 0), nx - 1)];
  const positions = new Float32Array(nx * nz * 3), normals = new Float32Array(nx * nz * 3);
  for (let k = 0; k < nz; k++) {
    for (let i = 0; i < nx; i++) {
      const v = (k * nx + i) * 3;
      positions.set([min[0] + i * dx, h(i, k), min[1] + k * dz], v);
      const sx = (h(i + 1, k) - h(i - 1, k)) / ((Math.min(i + 1, nx - 1) - Math.max(i - 1, 0)) * dx);
      const sz = (h(i, k + 1) - h(i, k - 1)) / ((Math.min(k + 1, nz - 1) - Math.max(k - 1, 0)) * dz);
      const len = Math.hypot(sx, 1, sz);
      normals.set([-sx / len, 1 / len, -sz / len], v);
    }
  }
  const indices = new Uint32Array((nx - 1) * (nz - 1) * 6);
  let n = 0;
  for (let k = 0; k + 1 < nz; k++) {
    for (let i = 0; i + 1 < nx; i++) {
      const a = k * nx + i, b = a + 1, c = a + nx, d = c + 1;
      indices.set([a, c, b, b, c, d], n);
      n += 6;
    }
  }
  return { positions, normals, indices };
}

/** Draws a scene's terrains in a WebGL2 context. */
export class TerrainMeshes {
  constructor(gl) {
    this.gl = gl;
    Object.assign(this, programWith(gl, VERT, FRAG, ['u_proj', 'u_view']));
    this.meshes = [];
  }

  /** The scene's terrains as the server lists them (`terrains` of its answer); [] for none. */
  set(terrains) {
    const gl = this.gl;
    for (const m of this.meshes) {
      gl.deleteVertexArray(m.vao);
      m.buffers.forEach((b) => gl.deleteBuffer(b));
    }
    this.meshes = terrains.map((t) => {
      const { positions, normals, indices } = terrainMesh(t);
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const buffers = [positions, normals].map((data, loc) => {
        const b = gl.createBuffer();
        gl.bindBuffer(gl.ARRAY_BUFFER, b);
        gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
        gl.enableVertexAttribArray(loc);
        gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
        return b;
      });
      const ib = gl.createBuffer();
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
      gl.bindVertexArray(null);
      return { vao, buffers: [...buffers, ib], count: indices.length };
    });
  }

  /** Draws with the camera's matrices (depth-tested, so particles above it stay in front). */
  draw(proj, view) {
    if (this.meshes.length === 0) return;
    const gl = this.gl;
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(this.u.u_proj, false, proj);
    gl.uniformMatrix4fv(this.u.u_view, false, view);
    for (const m of this.meshes) {
      gl.bindVertexArray(m.vao);
      gl.drawElements(gl.TRIANGLES, m.count, gl.UNSIGNED_INT, 0);
    }
    gl.bindVertexArray(null);
  }
}
