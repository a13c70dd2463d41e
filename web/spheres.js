// One sphere per canvas in WebGL2, drawn by the scene shader the server emits for a model
// (POST /api/glsl with shader: true): its vertex and fragment shaders and every uniform's value.
import {link} from './gl.js';

// Sets one active uniform from the server's value (numbers, vectors, or arrays of vectors).
function setUniform(gl, program, info, value) {
  const name = info.name.replace(/\[0\]$/, '');
  const location = gl.getUniformLocation(program, info.name);
  if (value === undefined || location === null) return;
  const flat = [value].flat(2);
  switch (info.type) {
    case gl.INT: return gl.uniform1i(location, flat[0]);
    case gl.FLOAT: return gl.uniform1f(location, flat[0]);
    case gl.FLOAT_VEC2: return gl.uniform2fv(location, flat);
    case gl.FLOAT_VEC3: return flat.length ? gl.uniform3fv(location, flat) : undefined;
    case gl.FLOAT_VEC4: return flat.length ? gl.uniform4fv(location, flat) : undefined;
    default: return name;  // samplers: the spheres-only shader never reads them
  }
}

export class SphereView {
  constructor(canvas) {
    this.canvas = canvas;
    this.gl = canvas.getContext('webgl2', {preserveDrawingBuffer: true, antialias: false});
    if (!this.gl) throw new Error('this browser has no WebGL2');
    this.source = null;
  }

  draw(answer) {
    const gl = this.gl;
    const [width, height] = answer.uniforms.u_resolution;
    this.canvas.width = width;
    this.canvas.height = height;
    const source = answer.vertex_shader + answer.fragment_shader;
    if (source !== this.source) {
      this.program = link(gl, answer.vertex_shader, answer.fragment_shader);
      this.source = source;
    }
    gl.viewport(0, 0, width, height);
    gl.useProgram(this.program);
    const count = gl.getProgramParameter(this.program, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < count; ++i) {
      const info = gl.getActiveUniform(this.program, i);
      setUniform(gl, this.program, info, answer.uniforms[info.name.replace(/\[0\]$/, '')]);
    }
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  /// RGBA bytes, row 0 at the top (as the canvas shows them and the CPU renderer writes them).
  pixels() {
    const copy = document.createElement('canvas');
    copy.width = this.canvas.width;
    copy.height = this.canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(this.canvas, 0, 0);
    return context.getImageData(0, 0, copy.width, copy.height).data;
  }
}

const decode = (c) => { c /= 255; return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4; };
const luminance = (p, i) => 0.2126 * decode(p[i]) + 0.7152 * decode(p[i + 1]) + 0.0722 * decode(p[i + 2]);

// A dark-blue → green → yellow ramp for t in [0, 1] (viridis-like, few stops).
function heat(t) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(x), stops.length - 2), f = x - i;
  return stops[i].map((c, k) => c + f * (stops[i + 1][k] - c));
}

/// |ΔL| of two equally sized pixel arrays as a heat map on `canvas`; returns the largest |ΔL|.
export function drawDifference(canvas, a, b, width, height) {
  canvas.width = width;
  canvas.height = height;
  const context = canvas.getContext('2d');
  const image = context.createImageData(width, height);
  const delta = new Float32Array(width * height);
  let max = 0;
  for (let p = 0; p < delta.length; ++p) {
    delta[p] = Math.abs(luminance(a, 4 * p) - luminance(b, 4 * p));
    max = Math.max(max, delta[p]);
  }
  for (let p = 0; p < delta.length; ++p) {
    const [r, g, bl] = heat(max > 0 ? delta[p] / max : 0);
    image.data.set([r, g, bl, 255], 4 * p);
  }
  context.putImageData(image, 0, 0);
  return max;
}
