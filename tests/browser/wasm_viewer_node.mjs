// SPDX-License-Identifier: MIT
// The viewer's WebAssembly engine under node: every bundle make_bundles
// wrote (each built-in game, both lanes, played natively) is re-simulated
// and must reach the native checksum at every tick, with the cosmetic
// debris layer throwing props all along in 3D; seeks back and forth land on
// the recorded state; the desync bundle names the bodies the native
// comparison named.
//
// usage: node wasm_viewer_node.mjs REWIND_VIEWER_JS BUNDLE_DIR
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';
import path from 'node:path';

const [viewerJs, dir] = process.argv.slice(2);
if (!viewerJs || !dir) {
  console.error('usage: node wasm_viewer_node.mjs REWIND_VIEWER_JS BUNDLE_DIR');
  process.exit(64);
}
const require = createRequire(import.meta.url);
const RewindViewer = require(path.resolve(viewerJs));
// The module's own loader would fetch() the .wasm, which node's fetch does
// not do for a file path: hand it the bytes.
const wasmPath = path.resolve(viewerJs).replace(/\.js$/, '.wasm');
const mod = await RewindViewer({ wasmBinary: readFileSync(wasmPath) });
const str = (ptr) => mod.UTF8ToString(ptr);
let failures = 0;
const fail = (message) => { console.error('FAIL: ' + message); ++failures; };

function load(file) {
  const bytes = readFileSync(path.join(dir, file));
  const ptr = mod._malloc(bytes.length);
  mod.HEAPU8.set(bytes, ptr);
  const rc = mod._rv_load(ptr, bytes.length, 50, 0);
  mod._free(ptr);
  if (rc !== 0) throw new Error(`${file}: ${str(mod._rv_error())}`);
}

for (const game of ['crates', 'arena', 'joust']) {
  load(`${game}.bin`);
  const length = mod._rv_length();
  let steps = 0;
  let debris = 0;
  while (mod._rv_step()) {
    ++steps;
    debris = Math.max(debris, mod._rv_debris_count());
    const p = mod._rv_position();
    if (mod._rv_check(p) !== 1 || str(mod._rv_checksum()) !== str(mod._rv_recorded_checksum())) {
      fail(`${game}: tick ${p - 1} gives ${str(mod._rv_checksum())}, native ${str(mod._rv_recorded_checksum())}`);
      break;
    }
  }
  if (steps !== length) fail(`${game}: stepped ${steps} of ${length} ticks`);
  // The cosmetic debris layer (3D games) throws props from hard impacts
  // while every checksum above stays native: it never touches the match.
  if (game === 'crates' && debris === 0) fail('crates: no debris from any impact');
  if (game === 'arena' && debris !== 0) fail('arena: debris in a 2D game');
  // Seeks back through the kept snapshots and forward again.
  for (const target of [length - 1, 3, Math.floor(length / 2), 1, length, 77, 0]) {
    mod._rv_seek(target);
    if (mod._rv_position() !== target) fail(`${game}: seek ${target} landed at ${mod._rv_position()}`);
    if (target > 0 && str(mod._rv_checksum()) !== str(mod._rv_recorded_checksum())) {
      fail(`${game}: after a seek to ${target} the checksum differs`);
    }
  }
  mod._rv_draw(0xff, 0, 0);
  const drawn = mod._rv_line_vertices() + mod._rv_triangle_vertices();
  if (drawn === 0) fail(`${game}: nothing drawn`);
  console.log(`${game} (${mod._rv_is_2d() ? '2D' : '3D'}): ${length} ticks, every checksum native;` +
              ` ${mod._rv_stat(0)} bodies; ${drawn} vertices drawn; up to ${debris} debris props;` +
              ` first mismatch ${mod._rv_first_mismatch()}`);
}

load('desync.bin');
const fields = mod._rv_open_desync();
const expected = readFileSync(path.join(dir, 'desync_bodies.txt'), 'utf8').trim().split('\n');
const expectedFields = Number(expected.pop().split(' ')[1]);
const bodies = Array.from(new Uint32Array(mod.HEAPU8.buffer, mod._rv_desync_bodies(),
  mod._rv_desync_body_count()));
if (fields !== expectedFields) fail(`desync: ${fields} differing fields, native ${expectedFields}`);
if (bodies.join(',') !== expected.join(',')) fail(`desync: bodies ${bodies} against native ${expected}`);
if (mod._rv_position() !== 101) fail(`desync: opened at ${mod._rv_position()}, not 101`);
console.log(`desync: ${fields} fields of bodies ${bodies.join(', ')} differ at tick ${mod._rv_desync_position()}`);
if (failures) {
  console.error(`${failures} failures`);
  process.exit(1);
}
console.log('PASS');
