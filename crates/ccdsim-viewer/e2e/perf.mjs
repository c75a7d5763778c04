// Measures how smoothly the viewer plays a run in headless Chromium: frames per second while
// playing at a given speed, and the time to the first frame. Prints figures; asserts nothing.
//
//   node perf.mjs RUN.ccd [--speed S] [--seconds N] [--boxes] [--screenshot OUT.png]
//
// Uses CCDSIM_BIN (default: the workspace's target/release/ccdsim).
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startViewer, launch } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const opt = (name, dflt) => { const k = args.indexOf(name); return k >= 0 ? args[k + 1] : dflt; };
const run = args[0];
if (!run) { console.error('usage: node perf.mjs RUN.ccd [--speed S] [--seconds N] [--boxes] [--screenshot OUT.png]'); process.exit(2); }
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/release/ccdsim');
const speed = Number(opt('--speed', '1')), seconds = Number(opt('--seconds', '3'));

const t0 = Date.now();
const viewer = await startViewer(BIN, run);
const url = viewer.url;
const indexed = (Date.now() - t0) / 1000;
const work = mkdtempSync(path.join(tmpdir(), 'ccdsim-perf-'));
const ctx = await launch(work, { width: 1280, height: 800 });
try {
  const page = await ctx.newPage();
  const p0 = Date.now();
  await page.goto(url);
  await page.waitForFunction(() => window.ccdsim && window.ccdsim.ready && window.ccdsim.frames() > 0, null, { timeout: 120000 });
  const firstFrame = (Date.now() - p0) / 1000;
  const meta = await page.evaluate(() => fetch('/api/meta').then((r) => r.json()));
  if (args.includes('--boxes')) await page.check('#boxes');
  await page.$eval('#speed', (el, v) => { el.value = v; el.dispatchEvent(new Event('input')); }, String(Math.log10(speed)));
  await page.click('#play');
  // Measure while the run lasts: stop short of its end at this speed.
  const ms = Math.min(seconds, (0.8 * (meta.end_time - meta.start_time)) / speed) * 1000;
  const r = await page.evaluate(async (ms) => {
    const f0 = window.ccdsim.frames(), t0 = window.ccdsim.time(), e0 = window.ccdsim.applied(), w0 = performance.now();
    await new Promise((res) => setTimeout(res, ms));
    const w = (performance.now() - w0) / 1000;
    return { fps: (window.ccdsim.frames() - f0) / w, drawMs: window.ccdsim.drawMs(), simRate: (window.ccdsim.time() - t0) / w, eventsPerSecond: (window.ccdsim.applied() - e0) / w };
  }, ms);
  const shot = opt('--screenshot', null);
  if (shot) await page.screenshot({ path: shot });
  console.log(JSON.stringify({ file: run, bodies: meta.bodies, events: meta.events, keyframe_interval: meta.keyframe_interval,
    server_ready_s: indexed, first_frame_s: firstFrame, speed, measured_s: ms / 1000, ...r }));
} finally {
  await ctx.close();
  viewer.process.kill();
  rmSync(work, { recursive: true, force: true });
}
