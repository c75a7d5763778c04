// The viewer on a run with moving walls (a steered run file, format version 10), written by the
// viewer crate's `wall_run` example (the run the Rust tests check playback against): a paddle
// (a segment) swung left and right every frame and a piston (a line) brought down and back
// up. The example reports every motion each wall had, so the test knows where each wall is at
// any time. Run through ./run.sh, which builds the example; or set WALL_RUN_BIN.

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
const WALL_RUN = process.env.WALL_RUN_BIN || path.resolve(here, '../../../target/debug/examples/wall_run');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const WALL = [200, 200, 200]; // src/render/colour.rs, assets/raster.js
const PADDLE = 0, PISTON = 1;

let work, server, context, page, run, meta;
const pageErrors = [];

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-walls-'));
  mkdirSync(OUT, { recursive: true });
  const file = path.join(work, 'walls.ccd');
  run = JSON.parse(execFileSync(WALL_RUN, [file]).toString());
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
const wallOnScreen = (k) => page.evaluate((k) => window.ccdsim.movingWall(k), k);

// Moving wall k's offset from its scene geometry at time t, from the run's report: its last
// motion that started at or before t.
function offsetAt(k, t) {
  const ps = run.pieces[k];
  let m = ps[0];
  for (const p of ps) if (p.time <= t) m = p;
  return m.offset.map((o, j) => o + m.velocity[j] * (t - m.time));
}

function assertOffset(k, got, t) {
  const want = offsetAt(k, t);
  for (let j = 0; j < 2; j++) {
    assert.ok(Math.abs(got[j] - want[j]) < 1e-9, `wall ${k} at t = ${t}: offset ${got} vs ${want}`);
  }
}

// Points along each wall on screen where it is drawn now: a quarter, half and three quarters
// along the paddle; three places along the piston's line inside the box.
async function wallSamples() {
  const paddle = await wallOnScreen(PADDLE);
  const piston = await wallOnScreen(PISTON);
  const along = (f) => ({ x: paddle.a.x + f * (paddle.b.x - paddle.a.x), y: paddle.a.y + f * (paddle.b.y - paddle.a.y) });
  const across = await Promise.all([2.5, 4, 5.5].map((x) => page.evaluate((x) => window.ccdsim.onScreen([x, 0]), x)));
  return {
    [PADDLE]: [0.25, 0.5, 0.75].map(along),
    [PISTON]: across.map((p) => ({ x: p.x, y: piston.point.y })),
  };
}

// True when a body (or its flash ring) is drawn within a few pixels of screen point q.
async function nearBody(q) {
  return page.evaluate(([{ x, y }, n]) => {
    for (let i = 0; i < n; i++) {
      const b = window.ccdsim.bodyOnScreen(i);
      // Vacant slots (r = 0) are not drawn.
      if (b.r > 0 && Math.hypot(b.x - x, b.y - y) < b.r + 6) return true;
    }
    return false;
  }, [q, meta.bodies]);
}

// Each wall is drawn at each of its sample points that no body covers (at least one each).
async function assertDrawnAt(samples, what) {
  for (const k of [PADDLE, PISTON]) {
    let seen = 0;
    for (const q of samples[k]) {
      if (await nearBody(q)) continue;
      assert.deepEqual(await pixel(q.x, q.y), WALL, `${what}: wall ${k} drawn at (${q.x}, ${q.y})`);
      seen++;
    }
    assert.ok(seen > 0, `${what}: wall ${k} has a sample point no body covers`);
  }
}

test('the page plays a run with moving walls to the end without an error', async () => {
  assert.deepEqual(meta.moving_walls, run.moving_walls);
  assert.equal(meta.events, run.events);
  assert.ok(run.pieces.every((p) => p.length > 30), 'both walls are steered');
  assert.ok(run.moving_wall_hits >= 5, `${run.moving_wall_hits} balls meet a moving wall`);
  await setSpeed(Math.log10(2));
  await page.click('#play');
  await page.waitForFunction(() => !window.ccdsim.playing(), null, { timeout: 60000 });
  assert.equal(await time(), meta.end_time);
  assert.equal(await page.evaluate(() => window.ccdsim.applied()), meta.events);
  // Played to the end, every wall edit applied on the way: the walls are where they end.
  for (const k of [PADDLE, PISTON]) assertOffset(k, (await wallOnScreen(k)).offset, meta.end_time);
  assert.deepEqual(pageErrors, []);
  assert.equal(await page.evaluate(() => window.ccdsim.error()), null);
});

test('moving walls are drawn where they are at two times, and no longer where they were', async () => {
  // At 0.6 s the paddle is near its right end and the piston high; at 1.8 s the paddle is
  // near its left end and the piston lower: some 1.4 m and 0.5 m apart.
  const [t1, t2] = [0.6, 1.8];
  await goTo(t1);
  for (const k of [PADDLE, PISTON]) assertOffset(k, (await wallOnScreen(k)).offset, t1);
  const first = await wallSamples();
  await assertDrawnAt(first, `t = ${t1}`);
  await page.screenshot({ path: path.join(OUT, 'viewer-walls-1.png') });
  await goTo(t2);
  for (const k of [PADDLE, PISTON]) assertOffset(k, (await wallOnScreen(k)).offset, t2);
  const second = await wallSamples();
  assert.ok(Math.abs(second[PADDLE][1].x - first[PADDLE][1].x) > 20, 'the paddle moved on screen');
  assert.ok(Math.abs(second[PISTON][1].y - first[PISTON][1].y) > 10, 'the piston moved on screen');
  await assertDrawnAt(second, `t = ${t2}`);
  // Where they were at t1 nothing of a wall is drawn now.
  for (const k of [PADDLE, PISTON]) {
    for (const q of first[k]) {
      assert.notDeepEqual(await pixel(q.x, q.y), WALL, `t = ${t2}: wall ${k} still drawn at its place of t = ${t1}`);
    }
  }
  await page.screenshot({ path: path.join(OUT, 'viewer-walls-2.png') });
  assert.deepEqual(pageErrors, []);
});

test('walls played across their edits are where a seek puts them, and the bodies too', async () => {
  // Edits of code 5 name walls 0 and 1, which are also bodies' slots: played, they must move
  // the walls and leave bodies 0 and 1 alone.
  const from = 1.0;
  await goTo(from);
  await setSpeed(0);
  await page.click('#play');
  await page.waitForFunction((to) => window.ccdsim.time() > to, from + 0.5, { timeout: 30000 });
  await page.click('#play');
  assert.ok(await page.evaluate(() => !window.ccdsim.playing()));
  await frames(page);
  const t = await time();
  const edits = run.pieces.map((ps) => ps.filter((p) => p.time > from && p.time <= t).length);
  assert.ok(edits.every((n) => n >= 4), `edits played: ${edits}`);
  const played = [];
  for (const k of [PADDLE, PISTON]) {
    const w = await wallOnScreen(k);
    assertOffset(k, w.offset, t);
    played.push(await page.evaluate((i) => window.ccdsim.bodyOnScreen(i), k));
  }
  await assertDrawnAt(await wallSamples(), `played to t = ${t}`);
  await goTo(t);
  for (const k of [PADDLE, PISTON]) {
    const sought = await page.evaluate((i) => window.ccdsim.bodyOnScreen(i), k);
    // The page plays in f64 from f32 snapshot positions: well under a pixel apart.
    assert.ok(Math.hypot(sought.x - played[k].x, sought.y - played[k].y) < 0.5,
      `body ${k} played to (${played[k].x}, ${played[k].y}), sought at (${sought.x}, ${sought.y})`);
  }
  assert.deepEqual(pageErrors, []);
});
