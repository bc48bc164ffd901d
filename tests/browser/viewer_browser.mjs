// SPDX-License-Identifier: MIT
// The viewer in a real browser: for each case, `rewind-replay view` serves a
// replay (or a view bundle) on a free port, headless Chromium opens it, and
// the page must load, re-simulate in WebAssembly and show, at every tick it
// is scrubbed to, the checksum the match recorded natively. A case with a
// desync report must open at its tick with exactly the bodies a native
// comparison named highlighted. Each case saves a screenshot.
//
// usage: node viewer_browser.mjs CONFIG.json
//   { "tool": rewind-replay, "viewerDir": DIR, "chromium": PATH, "shots": DIR,
//     "cases": [ { "name", "file", "desync"?: BIN, "expectBodies"?: [..] (the
//                  bundle holds a desync: open it and find these highlighted),
//                  "expectGame"?: NAME, "expect2d"?: bool } ] }
import { spawn } from 'node:child_process';
import { readFileSync, mkdirSync } from 'node:fs';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const config = JSON.parse(readFileSync(process.argv[2], 'utf8'));
mkdirSync(config.shots, { recursive: true });
let failures = 0;
const fail = (message) => { console.error('FAIL: ' + message); ++failures; };

/** Starts `rewind-replay view` and resolves with the address it prints. */
function serve(c) {
  const args = ['view', c.file, '--port', '0', '--viewer-dir', config.viewerDir];
  if (c.desync) args.push('--desync', c.desync);
  const child = spawn(config.tool, args, { stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  let err = '';
  child.stderr.on('data', (d) => { err += d; });
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`no address from ${config.tool}: ${err}`)), 20000);
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/ at (http:\/\/\S+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, url: m[1] });
      }
    });
    child.on('exit', (code) => reject(new Error(`${config.tool} exited ${code}: ${err}`)));
  });
}

const browser = await puppeteer.launch({
  executablePath: config.chromium,
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1280,800'],
});
try {
  for (const c of config.cases) {
    const started = Date.now();
    const { child, url } = await serve(c);
    const page = await browser.newPage();
    await page.setViewport({ width: 1280, height: 800 });
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    try {
      await page.goto(url, { waitUntil: 'load' });
      await page.waitForFunction(() => window.rewindViewer && (window.rewindViewer.error ||
        window.rewindViewer.seek), { timeout: 60000 });
      const loadError = await page.evaluate(() => window.rewindViewer.error);
      if (loadError) throw new Error('the page did not load: ' + loadError);
      const info = await page.evaluate(() => ({ length: window.rewindViewer.length(),
        game: document.getElementById('game').textContent }));
      if (c.expectGame && !info.game.startsWith(c.expectGame)) fail(`${c.name}: shows "${info.game}"`);
      // Scrub forward, back through the kept snapshots, to the end.
      const targets = [Math.floor(info.length / 3), 10, info.length, Math.floor(info.length / 2), 1];
      for (const t of targets) {
        const r = await page.evaluate((p) => {
          const v = window.rewindViewer;
          v.seek(p);
          return { position: v.position(), checksum: v.checksum(), recorded: v.recorded(),
            check: v.check(p) };
        }, t);
        if (r.position !== t || r.checksum !== r.recorded || r.check !== 1) {
          fail(`${c.name}: at tick ${t} the page shows ${JSON.stringify(r)}`);
        }
      }
      const mismatch = await page.evaluate(() => window.rewindViewer.firstMismatch());
      if (mismatch !== -1) fail(`${c.name}: first mismatch at ${mismatch}`);
      let note = `${info.length} ticks, checksums native at ${targets.join(', ')}`;
      if (c.expectBodies) {
        const d = await page.evaluate(() => window.rewindViewer.openDesync());
        const lit = await page.evaluate(() => window.rewindViewer.highlighted());
        if (JSON.stringify(d.bodies) !== JSON.stringify(c.expectBodies) ||
            JSON.stringify(lit) !== JSON.stringify(c.expectBodies)) {
          fail(`${c.name}: desync bodies ${d.bodies}, highlighted ${lit}, native ${c.expectBodies}`);
        }
        const rows = await page.$$eval('#desync-fields tr', (r) => r.length);
        if (rows < d.fields.length) fail(`${c.name}: ${rows} rows for ${d.fields.length} fields`);
        note += `; desync at tick ${d.position}: bodies ${d.bodies.join(', ')} highlighted, ` +
          `${d.fields.length} fields listed`;
      } else {
        await page.evaluate((p) => window.rewindViewer.seek(p), Math.floor(info.length * 0.6));
      }
      // A few frames drawn before the picture.
      const frames = await page.evaluate(() => window.rewindViewer.frames());
      await page.waitForFunction((f) => window.rewindViewer.frames() > f + 3, { timeout: 20000 }, frames);
      const shot = path.join(config.shots, `${c.name}.png`);
      await page.screenshot({ path: shot });
      if (errors.length) fail(`${c.name}: page errors: ${errors.join(' | ')}`);
      console.log(`${c.name}: ${note}; ${shot} (${((Date.now() - started) / 1000).toFixed(1)} s)`);
    } catch (e) {
      fail(`${c.name}: ${e.message}`);
    } finally {
      await page.close();
      child.kill('SIGTERM');
    }
  }
} finally {
  await browser.close();
}
if (failures) {
  console.error(`${failures} failures`);
  process.exit(1);
}
console.log('PASS');
