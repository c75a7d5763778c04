// The viewer on a run that adds and removes bodies (a steered run file, format version 9),
// written by the viewer crate's `slot_run` example (the run the Rust tests check playback
// against), which also reports each add and removal. Run through ./run.sh, which builds the
// example; or set SLOT_RUN_BIN.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { frames, openViewer, pixelAt, setSpeed as setSpeedOf, goTo as goToOn } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/debug/ccdsim');
const SLOT_RUN = process.env.SLOT_RUN_BIN || path.resolve(here, '../../../target/debug/examples/slot_run');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const BACKGROUND = [17, 20, 24];

let work, server, context, page, run;
const pageErrors = [];

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-slots-'));
  mkdirSync(OUT, { recursive: true });
  const file = path.join(work, 'slots.ccd');
  run = JSON.parse(execFileSync(SLOT_RUN, [file]).toString());
  ({ server, context, page } = await openViewer(BIN, file, path.join(work, 'profile'),
    (e) => pageErrors.push(e.message)));
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

const pixel = (x, y) => pixelAt(page, x, y);

const setSpeed = (log10) => setSpeedOf(page, log10);

const goTo = (t) => goToOn(page, t);

const paused = () => page.evaluate(() => !window.ccdsim.playing());

// Plays at 0.1× from `from` (s) until the clock passes `to`, then pauses: the events on the
// way are applied one by one as the page plays them (not from a snapshot).
async function playAcross(from, to) {
  await goTo(from);
  await setSpeed(-1);
  await page.click('#play');
  await page.waitForFunction((to) => window.ccdsim.time() > to, to, { timeout: 30000 });
  await page.click('#play');
  assert.ok(await paused());
  await frames(page);
}

test('the page plays a run that adds and removes bodies without an error', async () => {
  const meta = await page.evaluate(async () => (await fetch('/api/meta')).json());
  assert.equal(meta.slot_edits, true);
  assert.equal(meta.scene_bodies, run.scene_bodies);
  assert.ok(meta.bodies > meta.scene_bodies, `${meta.bodies} slots`);
  assert.equal(meta.events, run.events);
  // The whole run at 2×, then back to the start.
  await setSpeed(Math.log10(2));
  await page.click('#play');
  await page.waitForFunction(() => !window.ccdsim.playing(), null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => window.ccdsim.time()), meta.end_time);
  assert.equal(await page.evaluate(() => window.ccdsim.applied()), meta.events);
  await goTo(0);
  assert.deepEqual(pageErrors, []);
  assert.equal(await page.evaluate(() => window.ccdsim.error()), null);
});

test('a removed body is not drawn, whether played up to or sought', async () => {
  // A removal whose slot stays vacant for a while (bodies are added every 0.15 s).
  const r = run.removals.find((r) => !run.adds.some((a) => a.slot === r.slot && a.time >= r.time && a.time < r.time + 0.04));
  assert.ok(r, 'a removal');
  await goTo(r.time - 0.02);
  const before = await page.evaluate((i) => window.ccdsim.bodyOnScreen(i), r.slot);
  assert.ok(before.r > 0, `slot ${r.slot} holds a body before its removal`);
  for (const how of ['played', 'sought']) {
    if (how === 'played') await playAcross(r.time - 0.02, r.time + 0.005);
    else await goTo(r.time + 0.01);
    const s = await page.evaluate((i) => [window.ccdsim.bodyOnScreen(i), window.ccdsim.slot(i)], r.slot);
    assert.equal(s[0].r, 0, `${how}: slot ${r.slot} is not drawn`);
    assert.equal(s[1].radius, 0);
    // Where it stopped (a vacant slot stays there) is empty: no other body could be within
    // its radius of its centre so soon.
    assert.deepEqual(await pixel(s[0].x, s[0].y), BACKGROUND, `${how}: nothing drawn at (${s[0].x}, ${s[0].y})`);
  }
  await page.screenshot({ path: path.join(OUT, 'viewer-slots-removed.png') });
  assert.deepEqual(pageErrors, []);
});

test('an added body is drawn with its own radius, id and kinematic flag', async () => {
  const n0 = run.scene_bodies;
  const removedWithin = (a, dt) => run.removals.some((r) => r.slot === a.slot && r.time >= a.time && r.time <= a.time + dt);
  // The first body of a slot past the scene's (after the start, so that the page plays up
  // to it), and a kinematic body that stays for a while.
  const fresh = run.adds.find((a) => a.slot >= n0 && a.time > 0.1 && !run.adds.some((b) => b.slot === a.slot && b.time < a.time));
  const kin = run.adds.find((a) => a.kinematic && a.time > 0.1 && !removedWithin(a, 0.2));
  assert.ok(fresh && kin, 'the run has both');
  await goTo(fresh.time - 0.02);
  assert.equal((await page.evaluate((i) => window.ccdsim.slot(i), fresh.slot)).radius, 0, `slot ${fresh.slot} holds nothing yet`);
  for (const a of [fresh, kin]) {
    for (const how of ['played', 'sought']) {
      if (how === 'played') await playAcross(a.time - 0.02, a.time + 0.005);
      else await goTo(a.time + 0.01);
      const [s, on] = await page.evaluate((i) => [window.ccdsim.slot(i), window.ccdsim.bodyOnScreen(i)], a.slot);
      assert.deepEqual(s, { radius: a.radius, id: a.id, kinematic: a.kinematic }, `${how}: slot ${a.slot}`);
      assert.ok(on.r > 1, `${how}: drawn (${on.r} px)`);
      assert.notDeepEqual(await pixel(on.x, on.y), BACKGROUND, `${how}: pixels at slot ${a.slot}`);
    }
  }
  // The kinematic body does not fall (gravity is (0, −3) m/s²): its velocity is horizontal.
  const y0 = (await page.evaluate((i) => window.ccdsim.bodyOnScreen(i), kin.slot)).y;
  await goTo(kin.time + 0.15);
  const y1 = (await page.evaluate((i) => window.ccdsim.bodyOnScreen(i), kin.slot)).y;
  assert.ok(Math.abs(y1 - y0) < 1e-6, `the kinematic body stays level: ${y0} → ${y1}`);
  await page.screenshot({ path: path.join(OUT, 'viewer-slots.png') });
  assert.deepEqual(pageErrors, []);
});
