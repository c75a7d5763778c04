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
