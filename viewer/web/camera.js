// SPDX-License-Identifier: MIT
// Cameras for the viewer: an orbit camera for 3D worlds (y up; drag to
// turn, shift-drag or right-drag to pan, wheel to zoom) and a plane camera
// for 2D worlds (the x-y plane seen from +z; drag to pan, wheel to zoom).
// Matrices are column-major Float32Arrays, as WebGL takes them.

function multiply(a, b) {
  const out = new Float32Array(16);
  for (let c = 0; c < 4; ++c) {
    for (let r = 0; r < 4; ++r) {
      let sum = 0;
      for (let k = 0; k < 4; ++k) sum += a[k * 4 + r] * b[c * 4 + k];
      out[c * 4 + r] = sum;
    }
  }
  return out;
}

function perspective(fovY, aspect, near, far) {
  const f = 1 / Math.tan(fovY / 2);
  const out = new Float32Array(16);
  out[0] = f / aspect;
  out[5] = f;
  out[10] = (far + near) / (near - far);
  out[11] = -1;
  out[14] = (2 * far * near) / (near - far);
  return out;
}

function ortho(left, right, bottom, top, near, far) {
  const out = new Float32Array(16);
  out[0] = 2 / (right - left);
  out[5] = 2 / (top - bottom);
  out[10] = -2 / (far - near);
  out[12] = -(right + left) / (right - left);
  out[13] = -(top + bottom) / (top - bottom);
  out[14] = -(far + near) / (far - near);
  out[15] = 1;
  return out;
}

function lookAt(eye, target, up) {
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm = (a) => { const l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; };
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const z = norm(sub(eye, target));
  const x = norm(cross(up, z));
  const y = cross(z, x);
  return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
    -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
}

/** Bounds [min, max] of the positions in 16-byte vertices (x, y, z first). */
export function boundsOf(floats, strideFloats) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i + 2 < floats.length; i += strideFloats) {
    for (let k = 0; k < 3; ++k) {
      const v = floats[i + k];
      if (!Number.isFinite(v) || Math.abs(v) > 1e5) continue;
      if (v < lo[k]) lo[k] = v;
      if (v > hi[k]) hi[k] = v;
    }
  }
  if (!(lo[0] <= hi[0])) return [[-5, -5, -5], [5, 5, 5]];
  return [lo, hi];
}

export class Camera {
  constructor(canvas, planar) {
    this.canvas = canvas;
    this.planar = planar;
    this.target = [0, 0, 0];
    this.distance = 10;
    this.yaw = 0.6;
    this.pitch = 0.45;
    this.changed = true;
    this.attach();
  }

  /** Frames the box [lo, hi]. */
  fit(lo, hi) {
    this.target = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
    const radius = Math.max(0.5, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2);
    this.distance = this.planar ? radius * 1.1 : radius * 2.2;
    this.changed = true;
  }

  matrix() {
    const aspect = this.canvas.clientWidth / Math.max(1, this.canvas.clientHeight);
    if (this.planar) {
      const h = this.distance;
      const w = h * aspect;
      const [x, y] = this.target;
      return ortho(x - w, x + w, y - h, y + h, -1000, 1000);
    }
    const eye = [
      this.target[0] + this.distance * Math.cos(this.pitch) * Math.sin(this.yaw),
      this.target[1] + this.distance * Math.sin(this.pitch),
      this.target[2] + this.distance * Math.cos(this.pitch) * Math.cos(this.yaw),
    ];
    const proj = perspective(Math.PI / 4, aspect, this.distance / 200, this.distance * 50);
    return multiply(proj, lookAt(eye, this.target, [0, 1, 0]));
  }

  /** The light's direction for shading: over the viewer's shoulder. */
  light() {
    if (this.planar) return [0, 0, 1];
    const l = [Math.sin(this.yaw + 0.5), 0.9, Math.cos(this.yaw + 0.5)];
    const n = Math.hypot(...l);
    return l.map((v) => v / n);
  }

  pan(dx, dy) {
    const scale = (2 * this.distance) / Math.max(1, this.canvas.clientHeight);
    if (this.planar) {
      this.target[0] -= dx * scale;
      this.target[1] += dy * scale;
    } else {
      const right = [Math.cos(this.yaw), 0, -Math.sin(this.yaw)];
      const up = [-Math.sin(this.pitch) * Math.sin(this.yaw), Math.cos(this.pitch),
        -Math.sin(this.pitch) * Math.cos(this.yaw)];
      for (let k = 0; k < 3; ++k) this.target[k] += (-dx * right[k] + dy * up[k]) * scale * 0.5;
    }
    this.changed = true;
  }

  attach() {
    let last = null;
    this.canvas.addEventListener('contextmenu', (e) => e.preventDefault());
    this.canvas.addEventListener('pointerdown', (e) => {
      last = { x: e.clientX, y: e.clientY, pan: this.planar || e.shiftKey || e.button !== 0 };
      this.canvas.setPointerCapture(e.pointerId);
    });
    this.canvas.addEventListener('pointerup', () => { last = null; });
    this.canvas.addEventListener('pointermove', (e) => {
      if (!last) return;
      const dx = e.clientX - last.x;
      const dy = e.clientY - last.y;
      last.x = e.clientX;
      last.y = e.clientY;
      if (last.pan) {
        this.pan(dx, dy);
      } else {
        this.yaw -= dx * 0.008;
        this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + dy * 0.008));
        this.changed = true;
      }
    });
    this.canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.distance *= Math.exp(e.deltaY * 0.001);
      this.changed = true;
    }, { passive: false });
  }
}
