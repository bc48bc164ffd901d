// SPDX-License-Identifier: MIT
// WebGL2 drawing of the engine's debug-draw buffers (rewind/sim/debug_draw.h):
// lines and triangles of 16-byte vertices (x, y, z float32, colour
// 0xRRGGBBAA as a little-endian u32), points of 20 bytes (the same and a
// size in pixels). Solid triangles are shaded by their own facet normal
// (screen-space derivatives), so the engine sends no normals; they are
// drawn see-through, under the outlines.

const LINE_VS = `#version 300 es
in vec3 pos;
in vec4 col;
in float size;
uniform mat4 mvp;
out vec4 vcol;
void main() {
  gl_Position = mvp * vec4(pos, 1.0);
  gl_PointSize = size;
  vcol = col.wzyx;  // 0xRRGGBBAA read as bytes AA BB GG RR
}`;

const LINE_FS = `#version 300 es
precision mediump float;
in vec4 vcol;
uniform bool round_points;
out vec4 color;
void main() {
  if (round_points && length(gl_PointCoord - vec2(0.5)) > 0.5) discard;
  color = vcol;
}`;

const SOLID_VS = `#version 300 es
in vec3 pos;
in vec4 col;
uniform mat4 mvp;
out vec4 vcol;
out vec3 world;
void main() {
  gl_Position = mvp * vec4(pos, 1.0);
  vcol = col.wzyx;
  world = pos;
}`;

const SOLID_FS = `#version 300 es
precision mediump float;
in vec4 vcol;
in vec3 world;
uniform vec3 light;
out vec4 color;
void main() {
  vec3 n = normalize(cross(dFdx(world), dFdy(world)));
  float shade = 0.45 + 0.55 * abs(dot(n, light));
  color = vec4(vcol.rgb * shade, 0.55);
}`;

function compile(gl, vs, fs) {
  const program = gl.createProgram();
  for (const [type, text] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, text);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
      throw new Error('shader: ' + gl.getShaderInfoLog(shader));
    }
    gl.attachShader(program, shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    throw new Error('program: ' + gl.getProgramInfoLog(program));
  }
  return program;
}

/** One vertex array over a buffer of `stride`-byte vertices. */
function vertexArray(gl, program, stride, withSize) {
  const vao = gl.createVertexArray();
  const buffer = gl.createBuffer();
  gl.bindVertexArray(vao);
  gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
  const pos = gl.getAttribLocation(program, 'pos');
  const col = gl.getAttribLocation(program, 'col');
  gl.enableVertexAttribArray(pos);
  gl.vertexAttribPointer(pos, 3, gl.FLOAT, false, stride, 0);
  gl.enableVertexAttribArray(col);
  gl.vertexAttribPointer(col, 4, gl.UNSIGNED_BYTE, true, stride, 12);
  const size = gl.getAttribLocation(program, 'size');
  if (size >= 0) {
    if (withSize) {
      gl.enableVertexAttribArray(size);
      gl.vertexAttribPointer(size, 1, gl.FLOAT, false, stride, 16);
    } else {
      gl.disableVertexAttribArray(size);
      gl.vertexAttrib1f(size, 1.0);
    }
  }
  gl.bindVertexArray(null);
  return { vao, buffer, count: 0 };
}

export class Renderer {
  constructor(canvas) {
    const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    this.gl = gl;
    this.canvas = canvas;
    this.lineProgram = compile(gl, LINE_VS, LINE_FS);
    this.solidProgram = compile(gl, SOLID_VS, SOLID_FS);
    this.lines = vertexArray(gl, this.lineProgram, 16, false);
    this.points = vertexArray(gl, this.lineProgram, 20, true);
    this.solids = vertexArray(gl, this.solidProgram, 16, false);
  }

  /** Copies the module's buffers (views into its memory) to the GPU. */
  upload(lineBytes, triangleBytes, pointBytes) {
    const gl = this.gl;
    for (const [target, bytes, stride] of [
      [this.lines, lineBytes, 16], [this.solids, triangleBytes, 16], [this.points, pointBytes, 20]]) {
      gl.bindBuffer(gl.ARRAY_BUFFER, target.buffer);
      gl.bufferData(gl.ARRAY_BUFFER, bytes, gl.DYNAMIC_DRAW);
      target.count = bytes.byteLength / stride;
    }
  }

  /** Draws what upload() gave with the 4x4 column-major matrix `mvp`. */
  draw(mvp, light) {
    const gl = this.gl;
    const w = this.canvas.clientWidth;
    const h = this.canvas.clientHeight;
    if (this.canvas.width !== w || this.canvas.height !== h) {
      this.canvas.width = w;
      this.canvas.height = h;
    }
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clearColor(0.09, 0.1, 0.12, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    if (this.solids.count > 0) {
      gl.useProgram(this.solidProgram);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.solidProgram, 'mvp'), false, mvp);
      gl.uniform3fv(gl.getUniformLocation(this.solidProgram, 'light'), light);
      // Surfaces are see-through and write no depth: every outline, contact
      // and joint stays visible, however many walls are in front of it.
      gl.depthMask(false);
      gl.bindVertexArray(this.solids.vao);
      gl.drawArrays(gl.TRIANGLES, 0, this.solids.count);
      gl.depthMask(true);
    }
    gl.useProgram(this.lineProgram);
    gl.uniformMatrix4fv(gl.getUniformLocation(this.lineProgram, 'mvp'), false, mvp);
    gl.uniform1i(gl.getUniformLocation(this.lineProgram, 'round_points'), 0);
    gl.bindVertexArray(this.lines.vao);
    gl.drawArrays(gl.LINES, 0, this.lines.count);
    gl.uniform1i(gl.getUniformLocation(this.lineProgram, 'round_points'), 1);
    gl.disable(gl.DEPTH_TEST);  // contact points show through the shapes they are on
    gl.bindVertexArray(this.points.vao);
    gl.drawArrays(gl.POINTS, 0, this.points.count);
    gl.bindVertexArray(null);
  }
}
