// The viewer on a run where balls come to rest on planes and slide along them
// (settings.rest_speed, a run file of format version 11), written by the viewer crate's
// `rest_run` example (the run the Rust tests check playback against): a ball dropped on a
// floor rests after its fourth contact (t = 1.375 s) and slides on, another slides down a 30°
// incline and along the floor, and the first is kicked up at t = 3 s and rests again. The
// example reports every ball's position and support every 0.05 s. Under full gravity a
// resting ball would sink through the floor: the page must draw it on it. Run through
// ./run.sh, which builds the example; or set REST_RUN_BIN.

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
const REST_RUN = process.env.REST_RUN_BIN || path.resolve(here, '../../../target/debug/examples/rest_run');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const BACKGROUND = [17, 20, 24]; // src/render/colour.rs, assets/raster.js
const FLOOR = 0;

let work, server, context, page, run, meta;
const pageErrors = [];

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-resting-'));
  mkdirSync(OUT, { recursive: true });
  const file = path.join(work, 'resting.ccd');
  run = JSON.parse(execFileSync(REST_RUN, [file]).toString());
  ({ server, context, page } = await openViewer(BIN, file, path.join(work, 'profile'),
    (e) => pageErrors.push(e.message)));
  meta = await page.evaluate(async () => (await fetch('/api/meta')).json());
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

const pixel = (x, y) => pixelAt(page, x, y);
const setSpeed = (log10) => setSpeedOf(page, log10);
const goTo = (t) => goToOn(page, t);
const time = () => page.evaluate(() => window.ccdsim.time());
const bodyOnScreen = (i) => page.evaluate((i) => window.ccdsim.bodyOnScreen(i), i);
const onScreen = (p) => page.evaluate((p) => window.ccdsim.onScreen(p), p);

// Each ball is drawn where the run's report has it at frame f, within half a pixel.
async function assertAtFrame(f) {
  const frame = run.frames[f];
  for (let i = 0; i < frame.bodies.length; i++) {
    const got = await bodyOnScreen(i);
    const want = await onScreen(frame.bodies[i].pos);
    assert.ok(Math.hypot(got.x - want.x, got.y - want.y) < 0.5,
      `t = ${frame.time}: ball ${i} drawn at (${got.x}, ${got.y}), not (${want.x}, ${want.y})`);
  }
}

// Ball i, resting on the floor, is drawn on it: its lowest point on the floor's line, its
// centre painted, and nothing of it below the floor.
async function assertOnFloor(i, what) {
  const b = await bodyOnScreen(i);
  const floor = await onScreen([0, 0]);
  assert.ok(Math.abs(b.y + b.r - floor.y) < 1, `${what}: ball ${i}'s bottom at ${b.y + b.r}, the floor at ${floor.y}`);
  assert.notDeepEqual(await pixel(b.x, b.y), BACKGROUND, `${what}: ball ${i} drawn at its centre`);
  assert.deepEqual(await pixel(b.x, floor.y + 4), BACKGROUND, `${what}: nothing below the floor under ball ${i}`);
  assert.deepEqual(await page.evaluate((i) => window.ccdsim.acceleration(i), i), meta.slides[FLOOR],
    `${what}: ball ${i} slides along the floor`);
}

test('meta describes a run where bodies rest on walls', async () => {
  assert.equal(meta.rest_speed, 0.4);
  assert.deepEqual(meta.slides[FLOOR], [0, 0]);
  assert.equal(meta.slides[2], null, 'no ball rests on the side wall');
  assert.equal(meta.events, run.events);
  assert.equal(run.floor_rest, 1.375);
});

test('a ball at rest late in the run is drawn on the floor, not below it', async () => {
  const late = run.frames.length - 10;
  await goTo(run.frames[late].time);
  for (const i of [0, 1]) {
    assert.equal(run.frames[late].bodies[i].support, FLOOR);
    await assertOnFloor(i, `t = ${run.frames[late].time}`);
  }
  await assertAtFrame(late);
  await page.screenshot({ path: path.join(OUT, 'viewer-resting.png') });
  // Sought at other frames, before and after each rest and the kick, every ball is where
  // the simulation had it.
  for (const f of [10, 25, 28, 40, 61, 75, 100]) {
    await goTo(run.frames[f].time);
    await assertAtFrame(f);
  }
  assert.deepEqual(pageErrors, []);
});

test('played across the rests and the kick, the balls are where a seek puts them', async () => {
  // From before ball 0 comes to rest on the floor to after it is kicked and rests again:
  // the events' rest flags, applied as the page plays them, keep each ball on its slide.
  const from = 1.2;
  await goTo(from);
  await setSpeed(Math.log10(2));
  await page.click('#play');
  await page.waitForFunction((to) => window.ccdsim.time() > to, run.kick_time + 1.3, { timeout: 30000 });
  await page.click('#play');
  assert.ok(await page.evaluate(() => !window.ccdsim.playing()));
  await frames(page);
  const t = await time();
  const played = [await bodyOnScreen(0), await bodyOnScreen(1)];
  await assertOnFloor(0, `played to t = ${t}`);
  await assertOnFloor(1, `played to t = ${t}`);
  await goTo(t);
  for (const i of [0, 1]) {
    const sought = await bodyOnScreen(i);
    // The page plays in f64 from f32 snapshot positions: well under a pixel apart.
    assert.ok(Math.hypot(sought.x - played[i].x, sought.y - played[i].y) < 0.5,
      `ball ${i} played to (${played[i].x}, ${played[i].y}), sought at (${sought.x}, ${sought.y})`);
  }
  assert.deepEqual(pageErrors, []);
});

test('the page plays the resting run to the end without an error', async () => {
  await goTo(run.frames[run.frames.length - 20].time);
  await setSpeed(0);
  await page.click('#play');
  await page.waitForFunction(() => !window.ccdsim.playing(), null, { timeout: 30000 });
  assert.equal(await time(), meta.end_time);
  assert.equal(await page.evaluate(() => window.ccdsim.applied()), meta.events);
  await frames(page);
  await assertAtFrame(run.frames.length - 1);
  for (const i of [0, 1]) await assertOnFloor(i, 'at the end');
  assert.deepEqual(pageErrors, []);
  assert.equal(await page.evaluate(() => window.ccdsim.error()), null);
});
