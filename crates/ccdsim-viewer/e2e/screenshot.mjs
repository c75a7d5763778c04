// Saves a screenshot of the viewer showing a run, as the README's picture is made.
//
//   node screenshot.mjs RUN.ccd OUT.png [--at T | --event K] [--boxes] [--colour speed]
//                       [--width W] [--height H]
//
// --event K goes to the time of event K (0-based), where its pair is highlighted. Uses
// CCDSIM_BIN (default: the workspace's target/release/ccdsim).
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startViewer, launch, frames } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const opt = (name, dflt) => { const k = args.indexOf(name); return k >= 0 ? args[k + 1] : dflt; };
const [run, out] = args;
if (!run || !out) { console.error('usage: node screenshot.mjs RUN.ccd OUT.png [--at T | --event K] [--boxes] [--colour speed] [--width W] [--height H]'); process.exit(2); }
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/release/ccdsim');

const viewer = await startViewer(BIN, run);
const work = mkdtempSync(path.join(tmpdir(), 'ccdsim-shot-'));
const ctx = await launch(work, { width: Number(opt('--width', '1000')), height: Number(opt('--height', '600')) });
try {
  const page = await ctx.newPage();
  await page.goto(viewer.url);
  await page.waitForFunction(() => window.ccdsim && window.ccdsim.ready, null, { timeout: 120000 });
  let t = opt('--at', null);
  if (opt('--event', null) !== null) {
    const meta = await page.evaluate(() => fetch('/api/meta').then((r) => r.json()));
    const ev = await page.evaluate((k) => fetch(`/api/events?from=${k}&count=1`).then((r) => r.arrayBuffer()).then((b) => Array.from(new Float64Array(b))), Number(opt('--event')));
    if (ev.length < 4 + 4 * meta.dim) throw new Error(`no event ${opt('--event')}`);
    t = String(ev[0]);
  }
  if (t !== null) {
    await page.fill('#goto', t);
    await page.press('#goto', 'Enter');
    await page.waitForFunction((t) => window.ccdsim.time() === t, Number(t));
  }
  if (opt('--colour', null)) await page.selectOption('#colour', opt('--colour'));
  if (args.includes('--boxes')) {
    await page.check('#boxes');
    await page.waitForFunction(() => { const b = window.ccdsim.boxes(); return b.time === window.ccdsim.time() || b.error; });
    const b = await page.evaluate(() => window.ccdsim.boxes());
    if (b.error) throw new Error(`boxes: ${b.error}`);
  }
  await frames(page);
  await page.screenshot({ path: out });
  console.log(`wrote ${out} (t = ${await page.evaluate(() => window.ccdsim.time())} s)`);
} finally {
  await ctx.close();
  viewer.process.kill();
  rmSync(work, { recursive: true, force: true });
}
