// The viewer on a pool shot: `ccdsim gen table` (a nine-ball break), played with `ccdsim run
// --record`. The page draws the table and its pockets, each ball in its colour with a marker
// that turns with its spin, drops pocketed balls and plays at the chosen speed of time. Run
// through ./run.sh, which builds the binary; or set CCDSIM_BIN.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openViewer, pixelAt, frames } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/debug/ccdsim');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const CUE = [244, 241, 230]; // assets/pool.js
const POCKET = [5, 5, 5];

let work, server, context, page, summary;
const pageErrors = [];

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-pool-'));
  mkdirSync(OUT, { recursive: true });
  const scene = path.join(work, 'break.json');
  const run = path.join(work, 'break.ccd');
  execFileSync(BIN, ['gen', 'table', '--game', 'nine-ball', '--out', scene]);
  summary = JSON.parse(execFileSync(BIN, ['run', scene, '--record', run, '--json'], { encoding: 'utf8' }));
  ({ server, context, page } = await openViewer(BIN, run, path.join(work, 'profile'),
    (e) => pageErrors.push(e.message)));
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

async function at(t) {
  await page.evaluate((t) => window.ccdsim.setTime(t), t);
  await frames(page);
}

test('the page holds the recorded shot: its events, its end, its pocketed balls', async () => {
  const d = await page.evaluate(() => window.ccdsim.data());
  assert.equal(d.events.length, summary.events + 1, 'every event and the strike');
  assert.equal(d.events[0].type, 'strike');
  assert.equal(d.end, summary.time);
  const down = d.names.filter((_, i) => d.pocketed[i] !== null);
  assert.deepEqual(down, summary.pocketed.map(([ball]) => ball));
  assert.equal(d.table.pockets.length, 6);
});

test('balls are drawn where the shot puts them, and pocketed balls are gone', async () => {
  await at(0);
  const cue = await page.evaluate(() => window.ccdsim.ballOnScreen(0));
  assert.deepEqual(await pixelAt(page, cue.x, cue.y), CUE, 'the cue ball at its spot');
  const end = await page.evaluate(() => window.ccdsim.end());
  await at(end);
  const d = await page.evaluate(() => window.ccdsim.data());
  const [ball] = summary.pocketed[0];
  const i = d.names.indexOf(ball);
  assert.ok(i >= 0);
  // A pocketed ball's last state is its pocket's centre, drawn black now that it is gone.
  const where = await page.evaluate((i) => window.ccdsim.ballOnScreen(i), i);
  assert.deepEqual(await pixelAt(page, where.x, where.y), POCKET, `ball ${ball} dropped`);
  const text = await page.textContent('#pocketed');
  assert.ok(text.includes(ball), text);
  await page.screenshot({ path: path.join(OUT, 'pool.png') });
});

test('the markers turn with the balls', async () => {
  await at(0);
  const a = await page.evaluate(() => window.ccdsim.ballOnScreen(0));
  await at(0.05);
  const b = await page.evaluate(() => window.ccdsim.ballOnScreen(0));
  const rel = (s) => [(s.mx - s.x) / s.r, (s.my - s.y) / s.r];
  const [u, v] = [rel(a), rel(b)];
  assert.ok(Math.hypot(u[0] - v[0], u[1] - v[1]) > 0.1, `marker ${u} then ${v}`);
});

test('play runs time at the chosen speed and stops at the end', async () => {
  await at(0);
  await page.selectOption('#speed', '2');
  await page.click('#play');
  await page.waitForFunction(() => window.ccdsim.time() > 0.5);
  await page.click('#play');
  const t = await page.evaluate(() => window.ccdsim.time());
  assert.ok(t > 0.5 && t < summary.time, `t = ${t}`);
  const text = await page.textContent('#event');
  assert.match(text, /^event \d+ \/ \d+: /);
  assert.deepEqual(pageErrors, []);
});
