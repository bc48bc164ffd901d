// SPDX-License-Identifier: MIT
// Browser players in a real browser: headless Chromium opens one page per
// player; each page loads the client SDK (the build's client_web folder, an
// npm-style folder served as it is), joins a hosted match over WebSocket with
// its connect token, plays random inputs through simulated latency and
// loss, and reports how its match went. The server, the native bots and the
// checks of the replay are run_browser_players.sh's.
//
// usage: node browser_players.mjs CONFIG.json
//   { "chromium": PATH, "clientDir": DIR (client_web), "url": ws URL of the match,
//     "game": NAME, "tokens": [hex, ...] (one page each), "faults": {...},
//     "timeoutS": N, "out": FILE (the pages' results, JSON) }
// Exit status: 0 when every page finished the match with no desync.
import { readFileSync, writeFileSync } from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

const config = JSON.parse(readFileSync(process.argv[2], 'utf8'));

// The page: loads the SDK as a module, plays, and leaves its result in
// window.rewindResult. Its settings come in the URL's hash.
const PAGE = `<!doctype html><meta charset="utf-8"><title>Rewind browser player</title>
<script type="module">
import { loadRewind } from './rewind-client.js';
const settings = JSON.parse(decodeURIComponent(location.hash.slice(1)));
const events = { desync: 0, resynced: 0 };
let seed = settings.seed >>> 0;
const random = () => { seed = (Math.imul(seed, 1664525) + 1013904223) >>> 0; return seed / 4294967296; };
try {
  const rewind = await loadRewind();
  const spec = rewind.inputSpec(settings.game);
  // As a game's menu would: the step's code optimized before the match.
  await rewind.warmUp(settings.game);
  const client = rewind.connect({ url: settings.url, token: settings.token, game: settings.game,
                                  name: settings.name, faults: settings.faults });
  window.rewindClient = client;
  const finish = (outcome, reason) => {
    if (window.rewindResult) return;
    window.rewindResult = { outcome, reason, events, spec: spec.name, status: client.status(),
                            drawn: drawn };
  };
  let drawn = 0;
  client.on('desync', () => ++events.desync);
  client.on('resynced', () => ++events.resynced);
  client.on('matchEnded', (e) => finish('ended', e.reason));
  client.on('rejected', (e) => finish('rejected', e.reason));
  client.on('disconnected', (e) => finish('disconnected', e.reason));
  client.on('socketClosed', (e) => setTimeout(() => finish('socketClosed', e.reason), 3000));
  // A player who changes their mind every tenth of a second, within the
  // game's ranges; and a frame drawn now and then, as a game would.
  setInterval(() => {
    const input = {};
    for (const f of spec.fields) input[f.name] = f.min + Math.floor(random() * (f.max - f.min + 1));
    client.setInput(input);
    const frame = client.draw();
    if (frame && frame.triangles.length + frame.lines.length > 0) ++drawn;
  }, 100);
} catch (error) {
  window.rewindResult = { outcome: 'error', reason: String(error && error.stack || error) };
}
</script>`;

const types = { '.js': 'text/javascript', '.json': 'application/json', '.ts': 'text/plain' };
const server = http.createServer((request, response) => {
  const name = decodeURIComponent(new URL(request.url, 'http://x').pathname);
  if (name === '/favicon.ico') {
    response.writeHead(204);
    return response.end();
  }
  if (name === '/' || name === '/index.html') {
    response.writeHead(200, { 'Content-Type': 'text/html' });
    return response.end(PAGE);
  }
  const file = path.join(config.clientDir, path.basename(name));
  try {
    const body = readFileSync(file);
    response.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    response.end(body);
  } catch {
    response.writeHead(404);
    response.end();
  }
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const origin = `http://127.0.0.1:${server.address().port}/`;

const browser = await puppeteer.launch({
  executablePath: config.chromium,
  headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    // Every page plays in real time, though only one is in front.
    '--disable-background-timer-throttling', '--disable-renderer-backgrounding',
    '--disable-backgrounding-occluded-windows'],
});
let failures = 0;
const results = [];
try {
  const pages = [];
  for (let i = 0; i < config.tokens.length; ++i) {
    const page = await browser.newPage();
    page.on('pageerror', (error) => console.error(`page ${i}: ${error.message}`));
    page.on('console', (message) => {
      if (message.type() === 'error') console.error(`page ${i}: ${message.text()}`);
    });
    const settings = { url: config.url, token: config.tokens[i], game: config.game,
                       name: `browser-${i}`, faults: { ...config.faults, seed: 1000 + i },
                       seed: 77 + i };
    await page.goto(origin + '#' + encodeURIComponent(JSON.stringify(settings)));
    pages.push(page);
  }
  for (let i = 0; i < pages.length; ++i) {
    let result;
    try {
      await pages[i].waitForFunction(() => window.rewindResult, {
        timeout: config.timeoutS * 1000, polling: 200 });
      result = await pages[i].evaluate(() => window.rewindResult);
    } catch (error) {
      result = { outcome: 'timeout', reason: String(error.message),
                 status: await pages[i].evaluate(() => window.rewindClient?.status() ?? null) };
    }
    results.push(result);
    const s = result.status || {};
    const line = `browser ${i}: ${result.outcome} (${result.reason}); ` +
      `verified ${s.finalTicksVerified} final ticks, desyncs ${s.desyncs}, ` +
      `rollbacks ${s.rollbacks}, rtt ${Number(s.rttMs).toFixed(1)} ms, ` +
      `bytes in ${s.bytesIn} out ${s.bytesOut}, frames drawn ${result.drawn}`;
    console.log(line);
    if (result.outcome !== 'ended' || s.desyncs !== 0 || result.events?.desync !== 0) {
      console.error(`FAIL: browser ${i}: ${JSON.stringify(result)}`);
      ++failures;
    }
  }
} finally {
  await browser.close();
  server.close();
}
writeFileSync(config.out, JSON.stringify(results));
process.exit(failures === 0 ? 0 : 1);
