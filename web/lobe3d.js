// The 3-D lobe view: each model's BRDF over the outgoing hemisphere drawn in WebGL2 as the surface
// r(θ, φ)·ω(θ, φ) (r: the value over the largest value of all models), one colour per model, over
// the surface plane's grid with the normal, the incident direction and its mirror; the mouse (drag,
// wheel) or the keyboard (arrows, + and -) orbit and zoom the camera.
import {link} from './gl.js';

const kSurfaceVertex = `#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view, u_projection;
out vec3 v_normal;
void main() {
  v_normal = mat3(u_view) * a_normal;  // the view's rotation: light fixed to the camera
  gl_Position = u_projection * u_view * vec4(a_position, 1.0);
}`;

const kSurfaceFragment = `#version 300 es
precision mediump float;
in vec3 v_normal;
uniform vec3 u_colour;
uniform float u_alpha;
out vec4 colour;
void main() {
  float size = length(v_normal);
  vec3 n = size > 0.0 ? v_normal / size : vec3(0.0, 0.0, 1.0);
  if (!gl_FrontFacing) n = -n;  // two-sided: the inside of a lobe shows through the outside
  float lambert = max(dot(n, normalize(vec3(0.35, 0.55, 0.75))), 0.0);
  colour = vec4(u_colour * (0.35 + 0.65 * lambert), u_alpha);
}`;

const kLineVertex = `#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_colour;
uniform mat4 u_view, u_projection;
out vec3 v_colour;
void main() {
  v_colour = a_colour;
  gl_Position = u_projection * u_view * vec4(a_position, 1.0);
}`;

const kLineFragment = `#version 300 es
precision mediump float;
in vec3 v_colour;
out vec4 colour;
void main() { colour = vec4(v_colour, 1.0); }`;

const kAlpha = 0.55;
const kTarget = [0, 0, 0.3];  // the camera looks a little above the origin: the lobes sit above the plane
const kColours = {grid: '#d0d0d0', rim: '#a8a8a8', normal: '#555555', incident: '#e6a700', mirror: '#777777'};

const radians = (d) => (d * Math.PI) / 180;
const clamp = (v, lo, hi) => Math.min(Math.max(v, lo), hi);
const usable = (v) => (typeof v === 'number' && Number.isFinite(v) && v > 0 ? v : 0);
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => { const n = Math.hypot(...a); return n > 0 ? a.map((c) => c / n) : a; };

/// '#rgb' or '#rrggbb' as [r, g, b] in [0, 1] (grey for anything else).
function rgb(colour) {
  let hex = String(colour).replace(/^#/, '');
  if (hex.length === 3) hex = [...hex].map((c) => c + c).join('');
  if (!/^[0-9a-f]{6}$/i.test(hex)) return [0.5, 0.5, 0.5];
  return [0, 2, 4].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255);
}

// Column-major 4×4 matrices, as uniformMatrix4fv takes them.
function perspective(fovyDeg, aspect, near, far) {
  const f = 1 / Math.tan(radians(fovyDeg) / 2);
  return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0]);
}

function lookAt(eye, target, up) {
  const f = normalize(sub(target, eye)), s = normalize(cross(f, up)), u = cross(s, f);
  return new Float32Array([s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1]);
}

/// The camera on a sphere around kTarget: yaw about z from +x, pitch above the plane z = 0; z up on screen.
function eyeOf(yaw, pitch, distance) {
  const y = radians(yaw), p = radians(pitch);
  return [kTarget[0] + distance * Math.cos(p) * Math.cos(y), kTarget[1] + distance * Math.cos(p) * Math.sin(y), kTarget[2] + distance * Math.sin(p)];
}

/// How many φ columns the mesh has and whether it closes: a grid from φ0 to φ0 + 360° drops its
/// repeated last column; one that stops a step short of 360° wraps as it is.
function phiColumns(phiDeg) {
  const n = phiDeg.length;
  if (n < 3) return {columns: n, wrap: false};
  const span = phiDeg[n - 1] - phiDeg[0], step = span / (n - 1);
  if (Math.abs(span - 360) < 1e-3) return {columns: n - 1, wrap: n > 3};
  return {columns: n, wrap: Math.abs(span + step - 360) < 1e-3};
}

/// The largest usable value over every series (1 where there is none, so that all lies at the origin).
function largest(series) {
  let max = 0;
  for (const s of series) for (const row of s.values || []) for (const v of row || []) max = Math.max(max, usable(v));
  return max > 0 ? max : 1;
}

/// Triangle indices over a rows × columns grid (the last column joined to the first when wrap).
function gridIndices(rows, columns, wrap) {
  const indices = [];
  for (let i = 0; i + 1 < rows; ++i) {
    for (let j = 0; j < (wrap ? columns : columns - 1); ++j) {
      const j1 = (j + 1) % columns;
      const a = i * columns + j, b = (i + 1) * columns + j, c = (i + 1) * columns + j1, d = i * columns + j1;
      indices.push(a, b, c, a, c, d);  // counter-clockwise seen from outside for rising θ and φ
    }
  }
  return new Uint32Array(indices);
}

/// Per-vertex normals: the triangles' cross products (area-weighted) summed at their corners; a row
/// collapsed to one point (the pole, or a row of zeros) shares its sum; a zero normal falls back to ω.
function vertexNormals(points, directions, indices, rows, columns) {
  const normals = points.map(() => [0, 0, 0]);
  for (let t = 0; t < indices.length; t += 3) {
    const [a, b, c] = [indices[t], indices[t + 1], indices[t + 2]];
    const n = cross(sub(points[b], points[a]), sub(points[c], points[a]));
    for (const v of [a, b, c]) for (let k = 0; k < 3; ++k) normals[v][k] += n[k];
  }
  for (let i = 0; i < rows; ++i) {
    const row = normals.slice(i * columns, (i + 1) * columns), first = points[i * columns];
    if (!points.slice(i * columns, (i + 1) * columns).every((p) => Math.hypot(...sub(p, first)) < 1e-9)) continue;
    const sum = row.reduce((s, n) => [s[0] + n[0], s[1] + n[1], s[2] + n[2]], [0, 0, 0]);
    for (let j = 0; j < columns; ++j) normals[i * columns + j] = sum;
  }
  return normals.map((n, v) => (Math.hypot(...n) > 0 ? normalize(n) : directions[v]));
}

/// One model's surface: interleaved positions and normals, and triangle indices.
function lobeMesh(s, scale) {
  const thetas = (s.thetaDeg || []).map(radians), phis = (s.phiDeg || []).map(radians);
  const {columns, wrap} = phiColumns(s.phiDeg || []);
  const rows = thetas.length, points = [], directions = [];
  for (let i = 0; i < rows; ++i) {
    for (let j = 0; j < columns; ++j) {
      const w = [Math.sin(thetas[i]) * Math.cos(phis[j]), Math.sin(thetas[i]) * Math.sin(phis[j]), Math.cos(thetas[i])];
      const r = usable(s.values?.[i]?.[j]) / scale;
      directions.push(w);
      points.push(w.map((c) => c * r));
    }
  }
  const indices = gridIndices(rows, columns, wrap);
  const normals = vertexNormals(points, directions, indices, rows, columns);
  const vertices = new Float32Array(points.length * 6);
  points.forEach((p, v) => vertices.set([...p, ...normals[v]], 6 * v));
  return {vertices, indices};
}

/// The line segments' vertices (x, y, z, r, g, b): the plane's grid (circles to radius 1 and spokes),
/// then (from vertex `grid` on) the normal, the incident direction (length 1.2) and its mirror (−x, −y, z), dashed
/// (neither without an incident direction).
function lineVertices(incident) {
  const out = [];
  const segment = (a, b, colour) => out.push(...a, ...rgb(colour), ...b, ...rgb(colour));
  for (const radius of [0.25, 0.5, 0.75, 1]) {
    for (let k = 0; k < 72; ++k) {
      const a = radians(5 * k), b = radians(5 * (k + 1));
      segment([radius * Math.cos(a), radius * Math.sin(a), 0], [radius * Math.cos(b), radius * Math.sin(b), 0], radius === 1 ? kColours.rim : kColours.grid);
    }
  }
  for (let k = 0; k < 12; ++k) segment([0, 0, 0], [Math.cos(radians(30 * k)), Math.sin(radians(30 * k)), 0], kColours.grid);
  const grid = out.length / 6;
  segment([0, 0, 0], [0, 0, 1.1], kColours.normal);
  const light = normalize((incident || [0, 0, 0]).map((c) => (Number.isFinite(c) ? c : 0)));
  if (Math.hypot(...light) > 0) {
    segment([0, 0, 0], light.map((c) => 1.2 * c), kColours.incident);
    const mirror = [-light[0], -light[1], light[2]];
    for (let k = 0; k < 12; k += 2) segment(mirror.map((c) => (1.2 * k * c) / 12), mirror.map((c) => (1.2 * (k + 1) * c) / 12), kColours.mirror);
  }
  return {vertices: new Float32Array(out), grid};
}

/// A vertex array of interleaved float attributes (sizes: components per attribute) and optional indices.
function vertexArray(gl, vertices, sizes, indices) {
  const vao = gl.createVertexArray(), buffers = [gl.createBuffer()];
  gl.bindVertexArray(vao);
  gl.bindBuffer(gl.ARRAY_BUFFER, buffers[0]);
  gl.bufferData(gl.ARRAY_BUFFER, vertices, gl.STATIC_DRAW);
  const stride = 4 * sizes.reduce((a, b) => a + b, 0);
  let offset = 0;
  sizes.forEach((size, location) => {
    gl.enableVertexAttribArray(location);
    gl.vertexAttribPointer(location, size, gl.FLOAT, false, stride, offset);
    offset += 4 * size;
  });
  if (indices) {
    buffers.push(gl.createBuffer());
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffers[1]);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
  }
  gl.bindVertexArray(null);
  return {vao, buffers, count: indices ? indices.length : vertices.length / sizes.reduce((a, b) => a + b, 0)};
}

function release(gl, item) {
  gl.deleteVertexArray(item.vao);
  for (const buffer of item.buffers) gl.deleteBuffer(buffer);
}

export class LobeView {
  constructor(canvas) {
    this.canvas = canvas;
    this.gl = canvas.getContext('webgl2', {preserveDrawingBuffer: true, antialias: true});
    if (!this.gl) throw new Error('this browser has no WebGL2');
    this.surfaceProgram = link(this.gl, kSurfaceVertex, kSurfaceFragment);
    this.lineProgram = link(this.gl, kLineVertex, kLineFragment);
    this.yaw = 30;
    this.pitch = 25;
    this.distance = 3;
    this.meshes = [];
    this.setLines(null);
    this.listen();
    this.draw();
  }

  /// series: [{colour, thetaDeg, phiDeg, values: [row per θ][per φ]}]; incident: unit vector toward the light.
  setData(series, incident) {
    const gl = this.gl;
    for (const item of this.meshes) release(gl, item);
    const scale = largest(series);
    this.canvas.dataset.largest = String(scale);  // the value drawn at distance 1 (tests read it)
    this.meshes = series.map((s) => {
      const {vertices, indices} = lobeMesh(s, scale);
      return {...vertexArray(gl, vertices, [3, 3], indices), colour: rgb(s.colour)};
    });
    this.setLines(incident);
    this.draw();
  }

  setLines(incident) {
    if (this.lines) release(this.gl, this.lines);
    const {vertices, grid} = lineVertices(incident);
    this.lines = {...vertexArray(this.gl, vertices, [3, 3]), grid};
  }

  draw() {
    const gl = this.gl, {width, height} = this.canvas;
    this.sync();
    const view = lookAt(eyeOf(this.yaw, this.pitch, this.distance), kTarget, [0, 0, 1]);
    const projection = perspective(40, width / Math.max(height, 1), 0.05, 50);
    gl.viewport(0, 0, width, height);
    gl.clearColor(1, 1, 1, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    // First pass, opaque: the plane's grid, writing depth (seen through the lobes).
    gl.depthMask(true);
    gl.disable(gl.BLEND);
    this.drawLines(view, projection, 0, this.lines.grid);
    // Second pass, the lobes translucent with depth writes off rather than opaque or as wireframes:
    // lobes nest (a narrow specular lobe inside a broad one), and an opaque outer lobe would hide the
    // inner one while overlapping wireframes turn into moiré; see-through shaded surfaces keep every
    // lobe's shape and colour readable, and without depth writes no lobe hides another whatever the order.
    gl.depthMask(false);
    gl.enable(gl.BLEND);
    gl.blendFuncSeparate(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA, gl.ONE, gl.ONE_MINUS_SRC_ALPHA);  // the canvas stays opaque
    gl.enable(gl.CULL_FACE);
    this.useProgram(this.surfaceProgram, view, projection);
    gl.uniform1f(gl.getUniformLocation(this.surfaceProgram, 'u_alpha'), kAlpha);
    for (const mesh of this.meshes) {
      gl.uniform3fv(gl.getUniformLocation(this.surfaceProgram, 'u_colour'), mesh.colour);
      gl.bindVertexArray(mesh.vao);
      for (const face of [gl.FRONT, gl.BACK]) {  // each lobe's far side first, then its near side
        gl.cullFace(face);
        gl.drawElements(gl.TRIANGLES, mesh.count, gl.UNSIGNED_INT, 0);
      }
    }
    gl.disable(gl.CULL_FACE);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
    // Last, the normal, incident and mirror lines over the lobes: they would be dimmed inside them.
    this.drawLines(view, projection, this.lines.grid, this.lines.count - this.lines.grid);
    gl.bindVertexArray(null);
  }

  drawLines(view, projection, first, count) {
    this.useProgram(this.lineProgram, view, projection);
    this.gl.bindVertexArray(this.lines.vao);
    this.gl.drawArrays(this.gl.LINES, first, count);
  }

  useProgram(program, view, projection) {
    const gl = this.gl;
    gl.useProgram(program);
    gl.uniformMatrix4fv(gl.getUniformLocation(program, 'u_view'), false, view);
    gl.uniformMatrix4fv(gl.getUniformLocation(program, 'u_projection'), false, projection);
  }

  /// The camera's state on the element, for tests.
  sync() {
    this.canvas.dataset.yaw = String(this.yaw);
    this.canvas.dataset.pitch = String(this.pitch);
    this.canvas.dataset.distance = String(this.distance);
  }

  /// Turns the camera by dYaw and dPitch degrees and scales its distance by zoom, then redraws.
  orbit(dYaw, dPitch, zoom = 1) {
    this.yaw += dYaw;
    this.pitch = clamp(this.pitch + dPitch, -89, 89);
    this.distance = clamp(this.distance * zoom, 1.2, 10);
    this.draw();
  }

  listen() {
    const canvas = this.canvas;
    canvas.tabIndex = 0;
    canvas.setAttribute('role', 'img');
    canvas.setAttribute('aria-label', 'BRDF lobes over the outgoing hemisphere in 3-D, one colour per model: drag or use the arrow keys to rotate, the wheel or + and - to zoom');
    canvas.style.touchAction = 'none';
    let last = null;  // the pointer's position while a button is held
    canvas.addEventListener('pointerdown', (e) => {
      last = [e.clientX, e.clientY];
      try { canvas.setPointerCapture(e.pointerId); } catch { /* a synthetic pointer has nothing to capture */ }
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!last) return;
      const [dx, dy] = [e.clientX - last[0], e.clientY - last[1]];
      last = [e.clientX, e.clientY];
      this.orbit(-0.5 * dx, 0.5 * dy);  // the lobes follow the pointer
    });
    const end = (e) => {
      last = null;
      try { canvas.releasePointerCapture(e.pointerId); } catch { /* not captured */ }
    };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.orbit(0, 0, 1.1 ** Math.sign(e.deltaY));
    }, {passive: false});
    const keys = {ArrowLeft: [5, 0, 1], ArrowRight: [-5, 0, 1], ArrowUp: [0, -5, 1], ArrowDown: [0, 5, 1],
                  '+': [0, 0, 1 / 1.1], '=': [0, 0, 1 / 1.1], '-': [0, 0, 1.1], '_': [0, 0, 1.1]};
    canvas.addEventListener('keydown', (e) => {
      if (!keys[e.key] || e.ctrlKey || e.metaKey || e.altKey) return;
      e.preventDefault();
      this.orbit(...keys[e.key]);
    });
  }
}
