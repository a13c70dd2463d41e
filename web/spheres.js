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

// A full-screen triangle showing a texture's texels one to one, row 0 at the top.
const kQuadVertex = `#version 300 es
out vec2 uv;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  uv = 0.5 * p + 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}`;
const kQuadFragment = `#version 300 es
precision highp float;
in vec2 uv;
uniform sampler2D image;
out vec4 colour;
void main() { colour = texture(image, vec2(uv.x, 1.0 - uv.y)); }`;

export class SphereView {
  constructor(canvas) {
    this.canvas = canvas;
    this.gl = canvas.getContext('webgl2', {preserveDrawingBuffer: true, antialias: false});
    if (!this.gl) throw new Error('this browser has no WebGL2');
    this.programs = new Map();  // by source: a model's channels (and a slider's back and forth) compile once
  }

  draw(answer) {
    const gl = this.gl;
    const [width, height] = answer.uniforms.u_resolution;
    this.canvas.width = width;
    this.canvas.height = height;
    // Keyed without comments: the server's header comment lists the uniforms' values, which change
    // with every parameter while the program does not.
    const source = (answer.vertex_shader + answer.fragment_shader).replace(/\/\/[^\n]*/g, '');
    if (!this.programs.has(source)) {
      if (this.programs.size >= 8) {  // SwiftShader compiles a sphere's shader in 50-200 ms: keep the last few
        const [oldest, program] = this.programs.entries().next().value;
        gl.deleteProgram(program);
        this.programs.delete(oldest);
      }
      this.programs.set(source, link(gl, answer.vertex_shader, answer.fragment_shader));
    }
    this.program = this.programs.get(source);
    gl.viewport(0, 0, width, height);
    gl.useProgram(this.program);
    const count = gl.getProgramParameter(this.program, gl.ACTIVE_UNIFORMS);
    for (let i = 0; i < count; ++i) {
      const info = gl.getActiveUniform(this.program, i);
      setUniform(gl, this.program, info, answer.uniforms[info.name.replace(/\[0\]$/, '')]);
    }
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }

  /// A sphere whose parameters differ per channel (`render -p NAME=R,G,B`): each channel of the
  /// image from the render of that channel's parameters (answers: the three channels' /api/glsl),
  /// drawn on a scratch canvas, `pause()` awaited after each so that input is handled between them.
  async drawChannels(answers, pause) {
    this.scratch ??= new SphereView(document.createElement('canvas'));
    const images = [];
    for (const answer of answers) {
      this.scratch.draw(answer);
      images.push(this.scratch.pixels());
      await pause();
    }
    [this.canvas.width, this.canvas.height] = answers[0].uniforms.u_resolution;
    const composite = new Uint8Array(images[0].length);
    for (let i = 0; i < composite.length; ++i) composite[i] = i % 4 === 3 ? 255 : images[i % 4][i];
    this.show(composite);
  }

  /// Shows RGBA bytes (row 0 at the top) as they are.
  show(rgba) {
    const gl = this.gl, {width, height} = this.canvas;
    this.quad ??= link(gl, kQuadVertex, kQuadFragment);
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, texture);
    for (const [key, value] of [[gl.TEXTURE_MIN_FILTER, gl.NEAREST], [gl.TEXTURE_MAG_FILTER, gl.NEAREST],
                                [gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE], [gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE]])
      gl.texParameteri(gl.TEXTURE_2D, key, value);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, width, height, 0, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
    gl.viewport(0, 0, width, height);
    gl.useProgram(this.quad);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.deleteTexture(texture);
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

// The sRGB decoding of each 8-bit code, computed once.
const kLinear = Float32Array.from({length: 256}, (_, code) => {
  const c = code / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
});
const luminance = (p, i) => 0.2126 * kLinear[p[i]] + 0.7152 * kLinear[p[i + 1]] + 0.0722 * kLinear[p[i + 2]];

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
