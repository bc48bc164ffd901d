// SPDX-License-Identifier: MIT
// The Rewind viewer: loads a view bundle (a replay, optionally with a
// desync report; `rewind-replay view` serves one as bundle.bin), re-simulates
// it in WebAssembly (rewind_viewer.js) and draws the engine's debug draw.
// Play, pause, step, scrub to any tick, speed; every tick's checksum is
// compared with the recorded one.
//
// URL parameters: bundle=PATH (default bundle.bin), tick=N (start there),
// desync=1 (open at the bundle's desync report), live=MATCH (spectate a
// running match on the server that serves the page: rewind-server
// --live-bind; see live.js).
//
// window.rewindViewer is the page's API for scripts and tests: ready (a
// promise), seek(p), step(), play(), pause(), position(), start(),
// length(), checksum(), recorded(), check(p), firstMismatch(),
// verifiedThrough() (every tick before it re-simulated from the start and
// checked, whatever seeks jumped over), stats(),
// names(), openDesync(), highlighted(), frames(), live() (null unless
// live), error.
import { Camera, boundsOf } from './camera.js';
import { LiveLink } from './live.js';
import { Renderer } from './render.js';

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);

class Viewer {
  constructor(mod) {
    this.mod = mod;
    this.playing = false;
    this.speed = 1;
    this.carry = 0;
    this.highlight = [];
    this.highlightPtr = 0;
    this.stepMs = null;
    this.frameCount = 0;
    this.dirty = true;
    this.flags = 0;
    this.verified = 0;
  }

  str(ptr) { return this.mod.UTF8ToString(ptr); }

  async load(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`cannot fetch ${url}: ${response.status}`);
    this.loadBytes(new Uint8Array(await response.arrayBuffer()), 60, 0);
  }

  /** Calls `fn(ptr, size)` with `bytes` copied into the module's memory. */
  withBytes(bytes, fn) {
    const ptr = this.mod._malloc(bytes.length);
    this.mod.HEAPU8.set(bytes, ptr);
    try {
      return fn(ptr, bytes.length);
    } finally {
      this.mod._free(ptr);
    }
  }

  /**
   * Loads a view bundle: a snapshot kept every `keyframeEvery` ticks, at
   * most `maxKeyframes` (0: all). The first load sets up the drawing and
   * frames the scene; a reload (a live viewer starting over) keeps both.
   */
  loadBytes(bytes, keyframeEvery, maxKeyframes) {
    const rc = this.withBytes(bytes, (ptr, n) => this.mod._rv_load(ptr, n, keyframeEvery, maxKeyframes));
    if (rc !== 0) throw new Error('bundle refused: ' + this.str(this.mod._rv_error()));
    const first = !this.renderer;
    if (first) {
      this.planar = this.mod._rv_is_2d() === 1;
      this.renderer = new Renderer($('view'));
      this.camera = new Camera($('view'), this.planar);
    }
    this.describe();
    this.readFlags();
    this.draw();
    if (first) {
      const [lo, hi] = boundsOf(this.lineFloats(), 4);
      this.camera.fit(lo, hi);
    }
  }

  names() {
    const m = this.mod;
    const names = [];
    for (let p = 0; p < m._rv_players(); ++p) names.push(this.str(m._rv_player_name(p)));
    return names;
  }

  /** The header's player list and the scrub bar's range. */
  showNames() {
    const free = this.live ? '(free)' : null;
    $('players').textContent = this.names().map((n, p) => n || free || `player ${p}`).join(', ');
  }

  showRange() {
    $('length').textContent = this.mod._rv_length();
    $('scrub').min = this.mod._rv_start();
    $('scrub').max = this.mod._rv_length();
  }

  describe() {
    const m = this.mod;
    $('game').textContent = `${this.str(m._rv_game())} · ${m._rv_tick_rate()} Hz`;
    this.showNames();
    if (!m._rv_identity_matches()) {
      $('identity').hidden = false;
      $('identity').textContent = '⚠ ' + this.str(m._rv_identity_note());
    }
    this.showRange();
    if (m._rv_has_desync()) {
      $('desync').hidden = false;
      $('desync-headline').textContent = this.str(m._rv_desync_headline());
    }
  }

  readFlags() {
    this.flags = 0;
    for (const box of document.querySelectorAll('input[data-flag]')) {
      if (box.checked) this.flags |= Number(box.dataset.flag);
    }
    this.dirty = true;
  }

  lineFloats() {
    const m = this.mod;
    return new Float32Array(m.HEAPU8.buffer, m._rv_lines(), m._rv_line_vertices() * 4);
  }

  /** Asks the engine for the debug draw and hands it to the GPU. */
  draw() {
    const m = this.mod;
    m._rv_draw(this.flags, this.highlightPtr, this.highlight.length);
    const view = (ptr, bytes) => new Uint8Array(m.HEAPU8.buffer, ptr, bytes);
    this.renderer.upload(view(m._rv_lines(), m._rv_line_vertices() * 16),
      view(m._rv_triangles(), m._rv_triangle_vertices() * 16),
      view(m._rv_points(), m._rv_point_count() * 20));
    this.dirty = false;
  }

  setHighlight(bodies) {
    const m = this.mod;
    if (this.highlightPtr) m._free(this.highlightPtr);
    this.highlight = bodies.slice();
    this.highlightPtr = bodies.length ? m._malloc(bodies.length * 4) : 0;
    if (bodies.length) new Uint32Array(m.HEAPU8.buffer, this.highlightPtr, bodies.length).set(bodies);
    this.dirty = true;
  }

  timed(fn) {
    const start = performance.now();
    const steps = fn();
    if (steps > 0) {
      const ms = (performance.now() - start) / steps;
      this.stepMs = this.stepMs === null ? ms : this.stepMs * 0.9 + ms * 0.1;
    }
    this.dirty = true;
  }

  step() { this.timed(() => this.mod._rv_step()); }

  seek(position) {
    const from = this.mod._rv_position();
    this.timed(() => {
      this.mod._rv_seek(position);
      return Math.max(0, this.mod._rv_position() - from);
    });
  }

  back() { this.seek(this.mod._rv_position() - 1); }

  /** Advances playback by `dt` seconds of wall time. */
  advance(dt) {
    if (this.live && this.live.following) {
      this.follow(dt);
      return;
    }
    if (!this.playing) return;
    this.carry += dt * this.speed * this.mod._rv_tick_rate();
    let steps = Math.min(Math.floor(this.carry), 240);
    this.carry -= Math.floor(this.carry);
    this.timed(() => {
      let done = 0;
      while (steps-- > 0 && this.mod._rv_step()) ++done;
      return done;
    });
    if (this.mod._rv_position() >= this.mod._rv_length()) this.setPlaying(false);
  }

  /**
   * A live match: plays at the tick rate just behind the newest tick the
   * viewer has, and catches up in bigger steps when far behind (joining,
   * or after the tab slept).
   */
  follow(dt) {
    const m = this.mod;
    const rate = m._rv_tick_rate();
    const behind = m._rv_length() - m._rv_position();
    this.carry += dt * rate;
    let steps = Math.min(Math.floor(this.carry), behind);
    this.carry -= Math.floor(this.carry);
    if (behind > rate / 2) steps = Math.min(behind, 240);
    if (steps <= 0) return;
    this.timed(() => {
      let done = 0;
      while (steps-- > 0 && m._rv_step()) ++done;
      return done;
    });
  }

  setPlaying(on) {
    if (this.live) this.live.following = false;
    this.playing = on && this.mod._rv_position() < this.mod._rv_length();
    $('play').textContent = this.playing ? '❚❚' : '▶';
  }

  stats() {
    const s = (i) => this.mod._rv_stat(i);
    return { bodies: s(0), awake: s(1), pairs: s(2), contactPoints: s(3), joints: s(4),
      debris: this.mod._rv_debris_count() };
  }

  openDesync() {
    const m = this.mod;
    const count = m._rv_open_desync();
    if (count < 0) throw new Error(this.str(m._rv_error()));
    const bodies = Array.from(new Uint32Array(m.HEAPU8.buffer, m._rv_desync_bodies(),
      m._rv_desync_body_count()));
    const fields = [];
    for (let i = 0; i < count; ++i) {
      fields.push({ body: m._rv_desync_field_body(i), field: this.str(m._rv_desync_field_name(i)),
        expected: m._rv_desync_field_expected(i), actual: m._rv_desync_field_actual(i) });
    }
    this.setHighlight(bodies);
    this.showDesync(bodies, fields);
    this.frameBodies(bodies);
    this.dirty = true;
    return { position: m._rv_desync_position(), bodies, fields,
      clientChecksum: this.str(m._rv_desync_client_checksum()) };
  }

  /** Points the camera at the bodies (a few metres around them). */
  frameBodies(bodies) {
    const lo = [Infinity, Infinity, Infinity];
    const hi = [-Infinity, -Infinity, -Infinity];
    for (const b of bodies) {
      const ptr = this.mod._rv_body_center(b);
      if (!ptr) continue;
      const c = new Float32Array(this.mod.HEAPU8.buffer, ptr, 3);
      for (let k = 0; k < 3; ++k) {
        lo[k] = Math.min(lo[k], c[k] - 2);
        hi[k] = Math.max(hi[k], c[k] + 2);
      }
    }
    if (lo[0] <= hi[0]) this.camera.fit(lo, hi);
  }

  showDesync(bodies, fields) {
    $('desync-summary').textContent =
      `${fields.length} fields of ${bodies.length} bodies differ at tick ${this.mod._rv_desync_position()} ` +
      '(replay = expected, client = actual); the bodies are drawn in red';
    const table = $('desync-fields');
    table.replaceChildren();
    let last = -1;
    for (const f of fields) {
      if (f.body !== last) {
        const row = table.insertRow();
        row.className = 'body';
        row.insertCell().textContent = `body ${f.body}`;
        row.cells[0].colSpan = 3;
        last = f.body;
      }
      const row = table.insertRow();
      row.insertCell().textContent = f.field;
      row.insertCell().textContent = Number(f.expected).toPrecision(9);
      row.insertCell().textContent = Number(f.actual).toPrecision(9);
    }
  }

  /** Updates the panel to the present position. */
  panel() {
    const m = this.mod;
    const p = m._rv_position();
    $('position').textContent = p;
    $('scrub').value = p;
    $('checksum').textContent = this.str(m._rv_checksum());
    const recorded = this.str(m._rv_recorded_checksum());
    $('recorded').textContent = recorded || '—';
    const check = m._rv_check(p);
    const verdict = $('verdict');
    verdict.className = 'verdict' + (check === 1 ? ' match' : check === 2 ? ' mismatch' : '');
    verdict.textContent = check === 1 ? '✓ same as recorded' : check === 2 ? '✗ differs from the recording' : '';
    const first = m._rv_first_mismatch();
    $('first-mismatch').textContent = first >= 0 ? `first difference at tick ${first}` : '';
    if (!this.live) {
      $('verified').textContent = this.verified >= m._rv_length()
        ? `every tick re-simulated: ${first >= 0 ? 'differences found' : 'all as recorded'}`
        : `re-simulated from the start through tick ${this.verified}`;
    }
    const s = this.stats();
    $('stats').textContent = `${s.bodies} bodies, ${s.awake} awake, ${s.pairs} touching pairs, ` +
      `${s.contactPoints} contact points, ${s.joints} joints` +
      (this.planar ? '' : `; ${s.debris} debris props (cosmetic)`);
    $('step-ms').textContent = this.stepMs === null ? '–' : this.stepMs.toFixed(3);
    if (this.live) this.live.panel();
  }

  /**
   * Re-simulates a few ticks from the start beside the view, so that ticks
   * a seek jumped over (through the replay's keyframes) get their checks
   * too. A live viewer steps every tick itself.
   */
  verifySome() {
    const m = this.mod;
    if (this.live || this.verified >= m._rv_length()) return;
    const before = this.verified;
    this.verified = m._rv_verify(30);
    if (this.verified !== before) this.dirty = true;
  }

  frame(dt) {
    this.advance(dt);
    this.verifySome();
    if (this.dirty) {
      this.draw();
      this.panel();
    }
    this.renderer.draw(this.camera.matrix(), this.camera.light());
    ++this.frameCount;
  }
}

function wire(viewer) {
  $('play').onclick = () => viewer.setPlaying(!viewer.playing);
  $('step').onclick = () => { viewer.setPlaying(false); viewer.step(); };
  $('back').onclick = () => { viewer.setPlaying(false); viewer.back(); };
  $('scrub').oninput = (e) => { viewer.setPlaying(false); viewer.seek(Number(e.target.value)); };
  $('speed').onchange = (e) => { viewer.speed = Number(e.target.value); };
  $('open-desync').onclick = () => viewer.openDesync();
  for (const box of document.querySelectorAll('input[data-flag]')) box.onchange = () => viewer.readFlags();
  document.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'INPUT' && e.target.type !== 'checkbox') return;
    if (e.key === ' ') { viewer.setPlaying(!viewer.playing); e.preventDefault(); }
    if (e.key === 'ArrowRight') { viewer.setPlaying(false); viewer.step(); }
    if (e.key === 'ArrowLeft') { viewer.setPlaying(false); viewer.back(); }
  });
}

async function main() {
  const api = (window.rewindViewer = { error: null });
  let resolveReady;
  let rejectReady;
  api.ready = new Promise((resolve, reject) => { resolveReady = resolve; rejectReady = reject; });
  try {
    const mod = await RewindViewer();  // eslint-disable-line no-undef
    const viewer = new Viewer(mod);
    if (params.get('live')) {
      viewer.live = new LiveLink(viewer, params.get('live'));
      await viewer.live.begin();
    } else {
      await viewer.load(params.get('bundle') || 'bundle.bin');
    }
    wire(viewer);
    Object.assign(api, {
      seek: (p) => { viewer.seek(p); viewer.frame(0); },
      step: () => { viewer.step(); viewer.frame(0); },
      play: () => viewer.setPlaying(true),
      pause: () => viewer.setPlaying(false),
      position: () => mod._rv_position(),
      start: () => mod._rv_start(),
      length: () => mod._rv_length(),
      names: () => viewer.names(),
      live: () => (viewer.live ? viewer.live.report() : null),
      checksum: () => viewer.str(mod._rv_checksum()),
      recorded: () => viewer.str(mod._rv_recorded_checksum()),
      check: (p) => mod._rv_check(p),
      firstMismatch: () => mod._rv_first_mismatch(),
      verifiedThrough: () => viewer.verified,
      stats: () => viewer.stats(),
      openDesync: () => { const d = viewer.openDesync(); viewer.frame(0); return d; },
      highlighted: () => viewer.highlight.slice(),
      frames: () => viewer.frameCount,
    });
    if (params.get('tick')) viewer.seek(Number(params.get('tick')));
    if (params.get('desync') === '1' && mod._rv_has_desync()) viewer.openDesync();
    let last = performance.now();
    const loop = (now) => {
      viewer.frame(Math.min(0.25, (now - last) / 1000));
      last = now;
      requestAnimationFrame(loop);
    };
    viewer.frame(0);
    requestAnimationFrame(loop);
    $('status').textContent = '';
    resolveReady(api);
  } catch (e) {
    api.error = String(e.message || e);
    $('status').textContent = api.error;
    $('game').textContent = 'could not load';
    rejectReady(e);
  }
}

main();
