// SPDX-License-Identifier: MIT
// Runs an Emscripten program (one JavaScript file with its module inside,
// built for web and node: the determinism matrix's det_checksums) in
// headless Chromium and prints what it printed, so the matrix compares a
// browser's WebAssembly engine with the native one line for line.
//
// usage: node run_in_chromium.mjs PROGRAM_JS [ARGS...]
//   exit 0 when the program ran to its end in the page (its output then
//   decides), 1 when it aborted or the page failed.
import { createServer } from 'node:http';
import { readFileSync } from 'node:fs';
import puppeteer from 'puppeteer-core';

const [program, ...args] = process.argv.slice(2);
if (!program) {
  console.error('usage: node run_in_chromium.mjs PROGRAM_JS [ARGS...]');
  process.exit(64);
}
const script = readFileSync(program);
// The page sets up Module before the program's script runs: its arguments,
// where its output goes, and a flag once main has returned (postRun).
const page = `<!doctype html><meta charset="utf-8"><script>
window.lines = []; window.errors = []; window.done = false; window.aborted = null;
var Module = { arguments: ${JSON.stringify(args)},
  print: (l) => window.lines.push(l), printErr: (l) => window.errors.push(l),
  onAbort: (what) => { window.aborted = String(what); },
  postRun: [() => { window.done = true; }] };
</script><script src="program.js"></script>`;
const server = createServer((req, res) => {
  if (req.url === '/') {
    res.writeHead(200, { 'content-type': 'text/html' });
    res.end(page);
  } else if (req.url === '/program.js') {
    res.writeHead(200, { 'content-type': 'text/javascript' });
    res.end(script);
  } else {
    res.writeHead(404);
    res.end();
  }
});
await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
const browser = await puppeteer.launch({
  executablePath: process.env.REWIND_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  protocolTimeout: 1800000,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
let rc = 0;
try {
  const tab = await browser.newPage();
  tab.on('pageerror', (e) => { console.error('page error: ' + e); });
  await tab.goto(`http://127.0.0.1:${server.address().port}/`, { waitUntil: 'load', timeout: 600000 });
  await tab.waitForFunction(() => window.done || window.aborted, { timeout: 1800000, polling: 500 });
  const result = await tab.evaluate(() => ({ lines: window.lines, errors: window.errors,
    aborted: window.aborted }));
  if (result.lines.length) process.stdout.write(result.lines.join('\n') + '\n');
  if (result.errors.length) process.stderr.write(result.errors.join('\n') + '\n');
  if (result.aborted !== null) {
    console.error('run_in_chromium: the program aborted: ' + result.aborted);
    rc = 1;
  }
} catch (e) {
  console.error('run_in_chromium: ' + e.message);
  rc = 1;
} finally {
  await browser.close();
  server.close();
}
process.exit(rc);
