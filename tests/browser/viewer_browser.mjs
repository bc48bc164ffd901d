// SPDX-License-Identifier: MIT
// The viewer in a real browser: for each case, `rewind-replay view` serves a
// replay (or a view bundle) on a free port, headless Chromium opens it, and
// the page must load, re-simulate in WebAssembly and show, at every tick it
// is scrubbed to, the checksum the match recorded natively. A case with a
// desync report must open at its tick with exactly the bodies a native
// comparison named highlighted. Each case saves a screenshot.
//
// With "live", a match is running on a server with a live endpoint: one
// page watches it from its first seconds while the replay cases run, a second
// joins midway; both must follow the newest final tick with the server's
// checksum at every tick they re-simulate, show the players' names, and
// see the match end.
//
// usage: node viewer_browser.mjs CONFIG.json
//   { "tool": rewind-replay, "viewerDir": DIR, "chromium": PATH, "shots": DIR,
//     "cases": [ { "name", "file", "desync"?: BIN, "expectBodies"?: [..] (the
//                  bundle holds a desync: open it and find these highlighted),
//                  "expectGame"?: NAME, "expect2d"?: bool } ],
//     "live"?: { "name", "url" (the live endpoint), "match", "names": [..],
//                "ticks" (the match's length) } }
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
    // The live pages keep following while other pages are in front.
    '--disable-background-timer-throttling', '--disable-renderer-backgrounding',
    '--disable-backgrounding-occluded-windows',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--window-size=1280,800'],
});
/** Opens the live viewer on `c.match`; resolves once it has polled. */
async function openLive(c) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 800 });
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(`${c.url}/?live=${encodeURIComponent(c.match)}`, { waitUntil: 'load' });
  await page.waitForFunction(() => window.rewindViewer && (window.rewindViewer.error ||
    (window.rewindViewer.live && window.rewindViewer.live().polls > 0)), { timeout: 60000 });
  const loadError = await page.evaluate(() => window.rewindViewer.error);
  if (loadError) throw new Error('the live page did not load: ' + loadError);
  return { page, errors };
}

/** Every tick a live page re-simulated agreed with the server's checksum. */
async function liveChecks(name, page) {
  const r = await page.evaluate(() => {
    const v = window.rewindViewer;
    let checked = 0;
    let bad = -1;
    for (let p = v.start() + 1; p <= v.position(); ++p) {
      if (v.check(p) === 1) ++checked; else if (bad < 0) bad = p;
    }
    return { start: v.start(), position: v.position(), length: v.length(), checked, bad,
      mismatch: v.firstMismatch(), live: v.live(), names: v.names() };
  });
  if (r.bad >= 0 || r.mismatch !== -1) {
    fail(`${name}: tick ${r.bad} unchecked or differs: ${JSON.stringify(r)}`);
  }
  return r;
}

/**
 * Watches the live match: a page from its start, a second joining a few
 * seconds later. Returns a function that waits for the end and checks both.
 */
async function watchLive(c) {
  const started = Date.now();
  const first = await openLive(c);
  // A few seconds of the match, followed as it is made final.
  await first.page.waitForFunction(() => window.rewindViewer.position() > 240, { timeout: 60000 });
  const early = await liveChecks(c.name, first.page);
  if (JSON.stringify(early.names) !== JSON.stringify(c.names)) {
    fail(`${c.name}: names ${JSON.stringify(early.names)}, expected ${JSON.stringify(c.names)}`);
  }
  // Following, and within 5 s of the newest tick however loaded the machine.
  if (!early.live.following || early.live.lag > 300) {
    fail(`${c.name}: not following: ${JSON.stringify(early.live)}`);
  }
  const frames = await first.page.evaluate(() => window.rewindViewer.frames());
  await first.page.waitForFunction((f) => window.rewindViewer.frames() > f + 3, { timeout: 20000 },
    frames);
  const shot = path.join(config.shots, `${c.name}.png`);
  await first.page.screenshot({ path: shot });
  const second = await openLive(c);
  const joined = await second.page.evaluate(() => window.rewindViewer.start());
  if (joined <= 0) fail(`${c.name}: a viewer joining midway started at tick ${joined}`);
  console.log(`${c.name}: following at tick ${early.position} (${early.live.lag} ticks behind the ` +
    `newest final ${early.live.newestFinal}), ${early.checked} ticks checked; a second viewer ` +
    `joined at tick ${joined}; ${shot}`);
  return async () => {
    for (const [label, w] of [['first viewer', first], ['joined later', second]]) {
      try {
        await w.page.bringToFront();
        await w.page.waitForFunction((n) => {
          const v = window.rewindViewer;
          return v.live().gone !== null && v.position() >= n;
        }, { timeout: 120000, polling: 250 }, c.ticks);
      } catch (e) {
        fail(`${c.name} (${label}): the end never showed: ` +
          JSON.stringify(await w.page.evaluate(() => window.rewindViewer.live())));
        continue;
      }
      const end = await liveChecks(`${c.name} (${label})`, w.page);
      if (end.live.gone !== 'the match is over' || end.position !== c.ticks) {
        fail(`${c.name} (${label}): ended as ${JSON.stringify(end)}`);
      }
      if (w.errors.length) fail(`${c.name} (${label}): page errors: ${w.errors.join(' | ')}`);
      console.log(`${c.name} (${label}): ${end.checked} ticks ${end.start + 1}..${end.position} ` +
        `re-simulated with the server's checksums, ${end.live.polls} polls, ` +
        `${end.live.restarts} restarts; "${end.live.gone}"`);
      await w.page.close();
    }
    console.log(`${c.name}: ${((Date.now() - started) / 1000).toFixed(1)} s`);
  };
}

try {
  let liveEnd = null;
  if (config.live) {
    try {
      liveEnd = await watchLive(config.live);
    } catch (e) {
      fail(`${config.live.name}: ${e.message}`);
    }
  }
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
      // Seeks jump through the replay's keyframes; the page re-simulates
      // the rest from the start meanwhile: every tick ends up checked.
      await page.waitForFunction((n) => window.rewindViewer.verifiedThrough() >= n,
        { timeout: 120000, polling: 200 }, info.length);
      const all = await page.evaluate((n) => {
        const v = window.rewindViewer;
        let bad = -1;
        for (let p = 1; p <= n && bad < 0; ++p) if (v.check(p) !== 1) bad = p;
        return { bad, mismatch: v.firstMismatch() };
      }, info.length);
      if (all.bad !== -1 || all.mismatch !== -1) {
        fail(`${c.name}: tick ${all.bad} not as recorded (first mismatch ${all.mismatch})`);
      }
      let note = `${info.length} ticks, every one re-simulated as recorded, checksums native ` +
        `at ${targets.join(', ')}`;
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
  if (liveEnd) await liveEnd();
} finally {
  await browser.close();
}
if (failures) {
  console.error(`${failures} failures`);
  process.exit(1);
}
console.log('PASS');
