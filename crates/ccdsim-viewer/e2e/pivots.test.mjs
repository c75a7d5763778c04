// The viewer on a run where balls roll over the ends of shelves (format version 13, see
// ccdsim::motion::pivot), recorded by `ccdsim run` from a scene written here: ball 0 creeps off the
// end of a shelf at 0.1 m/s and turns about its end point for almost half a second before it
// comes off and falls; ball 1 reaches the end of another shelf at 1 m/s and turns for a
// shorter while. While a ball turns, the page must draw it on its circle about the end point
// (it integrates the turn itself, src/wire.rs), where the server's state has it (the library's
// exact Pivot), not on the parabola its turn started from: sought mid-turn, and played into
// the turn from before it. Run through ./run.sh, which builds the binary; or set CCDSIM_BIN.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { frames, openViewer, pixelAt, setSpeed, goTo } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/debug/ccdsim');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const BACKGROUND = [17, 20, 24]; // src/render/colour.rs, assets/raster.js
const PIVOT_A = 4; // bit of an event's rest flags (src/wire.rs)
const PIVOT_SECTION = 4; // opens a state answer's pivot section (src/wire.rs)
const R = 0.2;
const G = [0, -10];
const UNTIL = 4;

// A floor, and two level shelves at y = 1 with a ball resting on each a hair above it, sliding
// right: too slowly to fly off the end (v² < r·|g| = 2), so each rolls over it.
const SCENE = {
  dim: 2,
  settings: { restitution: 0.5, gravity: G, rest_speed: 1.0 },
  bodies: [
    { pos: [1.9, 1 + R + 1e-6], vel: [0.1, 0], radius: R },
    { pos: [5.5, 1 + R + 1e-6], vel: [1.0, 0], radius: R },
  ],
  walls: [
    { point: [0, 0], normal: [0, 1] },
    { a: [0, 1], b: [2, 1] },
    { a: [4, 1], b: [6, 1] },
  ],
};

let work, server, ctx, page, meta, events;
const turns = []; // per turn: its event, the ball, the end point, and when it ends
const pageErrors = [];

// The server's state (/api/state?q): the events applied, every ball's position (f32), and the
// turns of its pivot section (src/wire.rs), by ball.
const serverState = (q) => page.evaluate(async ([q, PIVOT_SECTION]) => {
  const ab = await (await fetch(`/api/state?${q}`)).arrayBuffer();
  const head = new Float64Array(ab, 0, 8);
  const [n, D] = [head[2], head[3]];
  const pos = new Float32Array(ab, 64, n * D);
  const rest = Math.ceil((64 + 8 * n * D) / 8) * 8;
  if (new Float64Array(ab, rest, 1)[0] !== 3) throw new Error(`no rest section at byte ${rest}`);
  const pivot = rest + 8 * (1 + n + n * D);
  const turns = {};
  if (ab.byteLength > pivot) {
    const p = new Float64Array(ab, pivot);
    if (p[0] !== PIVOT_SECTION) throw new Error(`not a pivot section at byte ${pivot}: ${p[0]}`);
    for (let j = 0; j < p[1]; j++) {
      const o = 2 + 8 * j;
      turns[p[o]] = { point: [p[o + 1], p[o + 2]], start: p[o + 3], pos: [p[o + 4], p[o + 5]], vel: [p[o + 6], p[o + 7]] };
    }
  }
  const balls = [];
  for (let i = 0; i < n; i++) balls.push(Array.from(pos.subarray(i * D, i * D + D)));
  return { applied: head[1], balls, turns };
}, [q, PIVOT_SECTION]);

const ccdsim = (f, arg) => page.evaluate(([f, arg]) => window.ccdsim[f](arg), [f, arg]);

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-pivots-'));
  mkdirSync(OUT, { recursive: true });
  const scene = path.join(work, 'roll.json');
  writeFileSync(scene, JSON.stringify(SCENE));
  const file = path.join(work, 'roll.ccd');
  execFileSync(BIN, ['run', scene, '--until', String(UNTIL), '--record', file, '-q']);
  const header = JSON.parse(execFileSync(BIN, ['export', file]).toString().split('\n')[0]);
  assert.equal(header.version, 13);
  ({ server, context: ctx, page } = await openViewer(BIN, file, path.join(work, 'profile'),
    (e) => pageErrors.push(e.message)));
  meta = await page.evaluate(async () => (await fetch('/api/meta')).json());
  const all = await page.evaluate(async (count) =>
    Array.from(new Float64Array(await (await fetch(`/api/events?from=0&count=${count}`)).arrayBuffer())), meta.events);
  const stride = 5 + 4 * meta.dim;
  events = [];
  for (let o = 0; o < all.length; o += stride) {
    events.push({ t: all[o], kind: all[o + 1], a: all[o + 2], b: all[o + 3], pos: all.slice(o + 4, o + 6),
      vel: all.slice(o + 6, o + 8), flags: all[o + stride - 1] });
  }
  events.forEach((e, k) => {
    if (!(e.flags & PIVOT_A)) return;
    const w = meta.walls[e.b];
    const u = [w.b[0] - w.a[0], w.b[1] - w.a[1]];
    const along = (e.pos[0] - w.a[0]) * u[0] + (e.pos[1] - w.a[1]) * u[1];
    const end = along >= 0.5 * (u[0] ** 2 + u[1] ** 2) ? w.b : w.a;
    const next = events.slice(k + 1).find((f) => f.a === e.a || (f.kind === 0 && f.b === e.a));
    turns.push({ ...e, k, end, until: next ? next.t : meta.end_time });
  });
});

after(async () => {
  if (ctx) await ctx.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

// The page's ball i at its time: its position (f64, as drawn) within 1e-6 relative of the
// server's (an f32 of the exact turn), on screen within half a pixel of it, and at the ball's
// radius from the end point it turns about. Returns the page's time and position.
async function assertAsServer(i, turn, what) {
  const t = await ccdsim('time');
  const s = await serverState(`t=${t}`);
  const got = await ccdsim('position', i);
  const want = s.balls[i];
  const err = Math.hypot(got[0] - want[0], got[1] - want[1]);
  assert.ok(err < 1e-6 * (1 + Math.hypot(...want)),
    `${what}, t = ${t}: ball ${i} at (${got}), the server has (${want}): ${err} m apart`);
  const drawn = await ccdsim('bodyOnScreen', i);
  const there = await ccdsim('onScreen', want);
  assert.ok(Math.hypot(drawn.x - there.x, drawn.y - there.y) < 0.5, `${what}, t = ${t}: drawn at (${drawn.x}, ${drawn.y}), the server's at (${there.x}, ${there.y})`);
  assert.ok(Math.abs(Math.hypot(got[0] - turn.end[0], got[1] - turn.end[1]) - R) < 1e-9, `${what}, t = ${t}: off the circle: (${got})`);
  assert.notDeepEqual(await pixelAt(page, drawn.x, drawn.y), BACKGROUND, `${what}: ball ${i} painted at its centre`);
  return { t, got, s };
}

// Where the parabola from the turn's start would have the ball at t.
const parabola = (turn, t) => {
  const dt = t - turn.t;
  return [0, 1].map((k) => turn.pos[k] + turn.vel[k] * dt + 0.5 * G[k] * dt * dt);
};

test('each ball rolls over its shelf\'s end: the events flag the turns', () => {
  assert.equal(meta.rest_speed, 1);
  const byBall = turns.map((u) => [u.a, u.b, u.end]).sort((x, y) => x[0] - y[0]);
  assert.deepEqual(byBall, [[0, 1, [2, 1]], [1, 2, [6, 1]]], 'one turn each, about its shelf\'s right end');
  for (const u of turns) {
    assert.equal(u.kind, 1, 'a wall event');
    assert.ok(u.until > u.t, `${JSON.stringify(u)}`);
  }
  const slow = turns.find((u) => u.a === 0);
  assert.ok(slow.until - slow.t > 0.3, `ball 0 turns for ${slow.until - slow.t} s`);
});

test('sought mid-turn, a turning ball is drawn on its circle, where the server has it', async () => {
  for (const u of turns) {
    for (const f of [0.1, 0.5, 0.9]) {
      const t = u.t + f * (u.until - u.t);
      await goTo(page, t);
      const turn = await ccdsim('turn', u.a);
      assert.ok(turn, `t = ${t}: ball ${u.a} turns on the page`);
      assert.deepEqual(turn.point, u.end);
      assert.equal(turn.start, u.t);
      const { got, s } = await assertAsServer(u.a, u, `sought, turn of ball ${u.a}`);
      assert.deepEqual(s.turns[u.a].point, u.end, 'the state\'s pivot section');
      assert.equal(s.turns[u.a].start, u.t);
      // The other ball turns in the page exactly when the server says so.
      for (const i of [0, 1]) assert.equal((await ccdsim('turn', i)) !== null, s.turns[i] !== undefined, `t = ${t}: ball ${i}`);
      if (u.a === 0 && f >= 0.5) {
        // Late in the long turn, nowhere near the parabola of its start.
        const p = parabola(u, t);
        assert.ok(Math.hypot(p[0] - got[0], p[1] - got[1]) > 0.05, `t = ${t}: (${got}) near the parabola's (${p})`);
      }
    }
  }
  await page.screenshot({ path: path.join(OUT, 'viewer-pivots.png') });
  assert.deepEqual(pageErrors, []);
});

test('before and after its turn, a ball does not turn', async () => {
  const slow = turns.find((u) => u.a === 0);
  for (const t of [slow.t - 0.05, slow.until + 0.05]) {
    await goTo(page, t);
    assert.equal(await ccdsim('turn', 0), null, `t = ${t}`);
    const s = await serverState(`t=${t}`);
    assert.equal(s.turns[0], undefined, `t = ${t}`);
  }
});

test('played into the turn from before it, the ball is where the server has it', async () => {
  // The page starts the turn from the event's flag as it plays it, and integrates it over
  // many frames from there.
  const slow = turns.find((u) => u.a === 0);
  const dur = slow.until - slow.t;
  await goTo(page, slow.t - 0.05);
  assert.equal(await ccdsim('turn', 0), null);
  await setSpeed(page, -1); // 0.1×: the turn lasts seconds on the wall clock
  await page.click('#play');
  await page.waitForFunction((to) => window.ccdsim.time() > to, slow.t + 0.6 * dur, { timeout: 30000 });
  await page.click('#play');
  assert.ok(await page.evaluate(() => !window.ccdsim.playing()));
  await frames(page);
  const { t } = await assertAsServer(0, slow, 'played');
  assert.ok(t > slow.t && t < slow.until, `paused at ${t}, not within the turn (${slow.t}, ${slow.until})`);
  assert.ok((await ccdsim('turn', 0)) !== null);
  // Played on past the turn's end: it falls (and lands) where the server has it.
  await setSpeed(page, 0);
  await page.click('#play');
  await page.waitForFunction((to) => window.ccdsim.time() > to, slow.until + 0.1, { timeout: 30000 });
  await page.click('#play');
  await frames(page);
  assert.equal(await ccdsim('turn', 0), null, 'the event after the turn ends it');
  const t2 = await ccdsim('time');
  const s = await serverState(`t=${t2}`);
  for (const i of [0, 1]) {
    const drawn = await ccdsim('bodyOnScreen', i);
    const there = await ccdsim('onScreen', s.balls[i]);
    assert.ok(Math.hypot(drawn.x - there.x, drawn.y - there.y) < 0.5, `t = ${t2}: ball ${i} drawn at (${drawn.x}, ${drawn.y}), the server's at (${there.x}, ${there.y})`);
  }
  assert.deepEqual(pageErrors, []);
  assert.equal(await page.evaluate(() => window.ccdsim.error()), null);
});
