// The viewer on a run where balls come to rest on planes and slide along them
// (settings.rest_speed, a run file of format version 11), written by the viewer crate's
// `rest_run` example (the run the Rust tests check playback against): a ball dropped on a
// floor rests after its fourth contact (t = 1.375 s) and slides on, another slides down a 30°
// incline and along the floor, and the first is kicked up at t = 3 s and rests again. The
// example reports every ball's position and support every 0.05 s. Under full gravity a
// resting ball would sink through the floor: the page must draw it on it.
//
// Then on the first 3 s of examples/shelves.json (balls rest on segments too, and fly off a
// shelf's end; format version 13, in which balls too slow to fly off roll over the end, see
// pivots.test.mjs), recorded by `ccdsim run`: a ball sliding along a shelf is
// drawn on it, and once it slides off the end it falls; the page's balls are where the
// server's states put them (tests/ledges.rs checks those against the simulation). Run through
// ./run.sh, which builds the example and the binary; or set REST_RUN_BIN and CCDSIM_BIN.

import { test, before, after, describe } from 'node:test';
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

describe('a format 13 run: balls on shelves fly off their ends', () => {
  const SHELVES = path.resolve(here, '../../../examples/shelves.json');
  const UNTIL = 3;
  let ctx, pg, m, events, off;
  const errors = [];

  // The server's state at time t (/api/state, src/wire.rs): the events applied, and per
  // ball its position (f32) and, from the rest section, its support (−1: none) and
  // acceleration.
  const serverState = (q) => pg.evaluate(async (q) => {
    const ab = await (await fetch(`/api/state?${q}`)).arrayBuffer();
    const head = new Float64Array(ab, 0, 8);
    const [n, D] = [head[2], head[3]];
    const pos = new Float32Array(ab, 64, n * D);
    const rest = Math.ceil((64 + 8 * n * D) / 8) * 8;
    const r = new Float64Array(ab, rest, 1 + n + n * D);
    if (r[0] !== 3) throw new Error(`no rest section at byte ${rest}`);
    const balls = [];
    for (let i = 0; i < n; i++) {
      balls.push({ pos: Array.from(pos.subarray(i * D, i * D + D)), support: r[1 + i],
        acc: Array.from(r.subarray(1 + n + i * D, 1 + n + i * D + D)) });
    }
    return { applied: head[1], balls };
  }, q);

  // Every ball is drawn where the server's state at the page's time has it, within half a
  // pixel (the page draws from f32 snapshot positions, in f64).
  async function assertAsServer(what) {
    const t = await pg.evaluate(() => window.ccdsim.time());
    const s = await serverState(`t=${t}`);
    for (let i = 0; i < s.balls.length; i++) {
      const got = await pg.evaluate((i) => window.ccdsim.bodyOnScreen(i), i);
      const want = await pg.evaluate((p) => window.ccdsim.onScreen(p), s.balls[i].pos);
      assert.ok(Math.hypot(got.x - want.x, got.y - want.y) < 0.5,
        `${what}, t = ${t}: ball ${i} drawn at (${got.x}, ${got.y}), the server has (${want.x}, ${want.y})`);
    }
    return s;
  }

  const ballOf = (i) => pg.evaluate((i) => window.ccdsim.bodyOnScreen(i), i);
  const at = (p) => pg.evaluate((p) => window.ccdsim.onScreen(p), p);
  const accelerationOf = (i) => pg.evaluate((i) => window.ccdsim.acceleration(i), i);

  before(async () => {
    const file = path.join(work, 'shelves.ccd');
    execFileSync(BIN, ['run', SHELVES, '--until', String(UNTIL), '--record', file, '-q']);
    const header = JSON.parse(execFileSync(BIN, ['export', file]).toString().split('\n')[0]);
    assert.equal(header.version, 13);
    ctx = await openViewer(BIN, file, path.join(work, 'profile-shelves'), (e) => errors.push(e.message));
    pg = ctx.page;
    m = await pg.evaluate(async () => (await fetch('/api/meta')).json());
    const all = await pg.evaluate(async (count) =>
      Array.from(new Float64Array(await (await fetch(`/api/events?from=0&count=${count}`)).arrayBuffer())), m.events);
    const stride = 5 + 4 * m.dim;
    events = [];
    for (let o = 0; o < all.length; o += stride) {
      events.push({ t: all[o], kind: all[o + 1], a: all[o + 2], b: all[o + 3], pos: all.slice(o + 4, o + 6),
        vel: all.slice(o + 6, o + 8), rests: all[o + stride - 1] });
    }
    // The first slide-off off a level shelf: a wall event without its rest flag of a ball
    // that, after the events before it, slid on that wall, and that does not roll over the
    // shelf's end (bit 2 of its flags: it turns about the end point).
    for (let k = 0; k < events.length && !off; k++) {
      const e = events[k];
      const w = m.walls[e.b];
      if (e.kind !== 1 || e.rests & 5 || !w || !w.a || w.a[1] !== w.b[1]) continue;
      const before = await serverState(`k=${k}`);
      if (before.balls[e.a].support !== e.b) continue;
      // The next event of the run, and the next one of that ball.
      const own = events.slice(k + 1).find((f) => f.a === e.a || (f.kind === 0 && f.b === e.a));
      const end = Math.abs(w.a[0] - e.pos[0]) < Math.abs(w.b[0] - e.pos[0]) ? w.a : w.b;
      off = { ...e, k, next: events[k + 1].t, own: own ? own.t : Infinity, wall: w, end };
    }
  });

  after(async () => {
    if (ctx) {
      await ctx.context.close();
      ctx.server.kill();
    }
  });

  test('meta: balls rest on the segments as on planes', () => {
    assert.equal(m.rest_speed, 0.5);
    assert.deepEqual(m.slides.slice(0, 3).map((s) => s === null), [false, true, true], 'floor and side walls');
    assert.ok(m.slides.slice(3).every((s) => s !== null), 'no segment is vertical');
    assert.ok(off, 'a ball slides off a level shelf');
    assert.ok(off.next > off.t && off.own > off.t + 0.5 && off.t < UNTIL - 0.5, `${JSON.stringify(off)}`);
  });

  test('a ball on a shelf is drawn on it, sliding along it', async () => {
    await goToOn(pg, off.t - 0.1);
    const s = await assertAsServer('sliding');
    assert.equal(s.balls[off.a].support, off.b);
    assert.deepEqual(await accelerationOf(off.a), m.slides[off.b]);
    // Its lowest point on the shelf's line, its centre painted.
    const b = await ballOf(off.a);
    const shelf = await at([s.balls[off.a].pos[0], off.wall.a[1]]);
    assert.ok(Math.abs(b.y + b.r - shelf.y) < 1, `ball ${off.a}'s bottom at ${b.y + b.r}, the shelf at ${shelf.y}`);
    assert.notDeepEqual(await pixelAt(pg, b.x, b.y), BACKGROUND);
    await pg.screenshot({ path: path.join(OUT, 'viewer-shelves.png') });
  });

  test('past the end of the shelf it falls', async () => {
    // Half-way from the slide-off to the next event of the run, and later in its fall.
    for (const t of [(off.t + off.next) / 2, off.t + 0.3]) {
      await goToOn(pg, t);
      const s = await assertAsServer('falling');
      assert.equal(s.balls[off.a].support, -1, `t = ${t}`);
      assert.deepEqual(s.balls[off.a].acc, m.gravity);
      assert.deepEqual(await accelerationOf(off.a), m.gravity);
      const b = await ballOf(off.a);
      const end = await at(off.end);
      assert.ok((b.x - end.x) * Math.sign(off.vel[0]) > 0, `t = ${t}: ball ${off.a} at x = ${b.x}, not past the end at ${end.x}`);
    }
    // 0.3 s after it left, it is 0.44 m lower: its centre well below the shelf's line.
    const low = await ballOf(off.a);
    const end = await at(off.end);
    assert.ok(low.y - end.y > 10, `ball ${off.a} at y = ${low.y}, the shelf's end at ${end.y}`);
    assert.deepEqual(errors, []);
  });

  test('played across the slide-off, the balls are where the server has them', async () => {
    await goToOn(pg, off.t - 0.2);
    assert.deepEqual(await accelerationOf(off.a), m.slides[off.b]);
    await setSpeedOf(pg, 0);
    await pg.click('#play');
    await pg.waitForFunction((to) => window.ccdsim.time() > to, off.t + 0.3, { timeout: 30000 });
    await pg.click('#play');
    await frames(pg);
    const t = await pg.evaluate(() => window.ccdsim.time());
    assert.ok(t < off.own, `played to ${t}, past ball ${off.a}'s next event at ${off.own}`);
    await assertAsServer('played');
    assert.deepEqual(await accelerationOf(off.a), m.gravity, 'the slide-off\'s event let it fall');
    assert.deepEqual(errors, []);
    assert.equal(await pg.evaluate(() => window.ccdsim.error()), null);
  });
});
