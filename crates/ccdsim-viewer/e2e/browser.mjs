// Shared by the e2e tests and the scripts: start `ccdsim view` and a headless Chromium.
import { spawn } from 'node:child_process';
import { chromium } from 'playwright-core';

// Chromium as the machine's probe runs it: no sandbox (root), no GPU, no network chatter.
export const CHROMIUM_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic',
  '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// Starts `bin view run --port 0`; resolves with { url, process } once it prints its URL.
export function startViewer(bin, run) {
  return new Promise((resolve, reject) => {
    const child = spawn(bin, ['view', run, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '', err = '';
    const timer = setTimeout(() => { child.kill(); reject(new Error(`ccdsim view printed no URL: ${err}`)); }, 120000);
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/^(http:\/\/127\.0\.0\.1:\d+\/)\n/);
      if (m) { clearTimeout(timer); resolve({ url: m[1], process: child }); }
    });
    child.stderr.on('data', (d) => { err += d; });
    child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`ccdsim view exited with ${code}: ${err}`)); });
  });
}

// A fresh headless Chromium profile in `profileDir` with a page of the given size.
export function launch(profileDir, viewport = { width: 1000, height: 640 }) {
  return chromium.launchPersistentContext(profileDir, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: CHROMIUM_ARGS,
    viewport,
    deviceScaleFactor: 1,
  });
}

// Waits until the page has drawn `n` more frames.
export async function frames(page, n = 2) {
  const f = await page.evaluate(() => window.ccdsim.frames());
  await page.waitForFunction(([f, n]) => window.ccdsim.frames() >= f + n, [f, n]);
}

// Opens `run` in `ccdsim view` (binary `bin`) and a fresh headless page on it (profile in
// `profileDir`), once the page says it is ready; the page's errors go to `onError`.
export async function openViewer(bin, run, profileDir, onError) {
  const viewer = await startViewer(bin, run);
  const context = await launch(profileDir);
  const page = await context.newPage();
  page.on('pageerror', onError);
  await page.goto(viewer.url);
  await page.waitForFunction(() => window.ccdsim && window.ccdsim.ready);
  return { url: viewer.url, server: viewer.process, context, page };
}

// The colour [r, g, b] of the canvas pixel at (x, y), in the page's pixels.
export const pixelAt = (page, x, y) =>
  page.evaluate(([x, y]) => Array.from(document.getElementById('view').getContext('2d')
    .getImageData(Math.floor(x), Math.floor(y), 1, 1).data.slice(0, 3)), [x, y]);

// Sets the speed slider to 10^log10 times real time.
export async function setSpeed(page, log10) {
  await page.$eval('#speed', (el, v) => { el.value = v; el.dispatchEvent(new Event('input')); }, String(log10));
}

// Types `t` into "go to", presses Enter and waits until the page is there and has drawn it.
export async function goTo(page, t) {
  await page.fill('#goto', String(t));
  await page.press('#goto', 'Enter');
  await page.waitForFunction((t) => window.ccdsim.time() === t, t);
  await frames(page);
}
