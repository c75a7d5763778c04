// End-to-end tests of `ccdsim view` in a real headless Chromium (Debian's chromium driven by
// playwright-core). Run through ./run.sh, which builds the binary; or set CCDSIM_BIN.
//
// The page under test is the one embedded in the binary; the run is a billiard break recorded
// by `ccdsim run --record`; geometry comes from the page's own camera (window.ccdsim) and the
// pixels from the canvas itself.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startViewer, launch, frames, pixelAt, setSpeed as setSpeedOf, goTo as goToOn } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/debug/ccdsim');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const BACKGROUND = [17, 20, 24]; // src/render/colour.rs, assets/raster.js
const FLASH_FILL = [255, 255, 255];

let work, server, url, context, page;

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-'));
  mkdirSync(OUT, { recursive: true });
  const run = path.join(work, 'break.ccd');
  execFileSync(BIN, ['run', '--until', '6', '--record', run, '--quiet']);
  const viewer = await startViewer(BIN, run);
  url = viewer.url;
  server = viewer.process;
  context = await launch(path.join(work, 'profile'));
  page = await context.newPage();
  page.on('pageerror', (e) => { throw e; });
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

async function api(p) {
  const r = await fetch(new URL(p, url));
  assert.equal(r.status, 200, `${p}: HTTP ${r.status}`);
  return r;
}

const pixel = (x, y) => pixelAt(page, x, y);

// A hash of the whole canvas, to tell pictures apart.
const canvasHash = () =>
  page.evaluate(() => {
    const c = document.getElementById('view');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let h = 2166136261;
    for (let i = 0; i < d.length; i += 4) h = Math.imul(h ^ (d[i] | (d[i + 1] << 8) | (d[i + 2] << 16)), 16777619);
    return h >>> 0;
  });

// Simulated seconds per wall second over `ms`, measured by the page's own clock.
const simRate = (ms) =>
  page.evaluate(async (ms) => {
    const t0 = window.ccdsim.time(), w0 = performance.now();
    await new Promise((r) => setTimeout(r, ms));
    return (window.ccdsim.time() - t0) / ((performance.now() - w0) / 1000);
  }, ms);

const setSpeed = (log10) => setSpeedOf(page, log10);

const goTo = (t) => goToOn(page, t);

async function paused() {
  if (await page.evaluate(() => window.ccdsim.playing())) await page.click('#play');
}

test('the page loads the recorded break', async () => {
  const res = await page.goto(url);
  assert.equal(res.status(), 200);
  await page.waitForFunction(() => window.ccdsim && window.ccdsim.ready);
  const meta = await (await api('api/meta')).json();
  assert.equal(meta.dim, 2);
  assert.equal(meta.bodies, 16);
  assert.ok(meta.events > 50, `${meta.events} events`);
  assert.equal(await page.textContent('#events'), `event 0 / ${meta.events}`);
  assert.equal(await page.evaluate(() => window.ccdsim.error()), null);
  // Nothing but the embedded page and its API was asked for.
  assert.match(await page.content(), /<canvas id="view"/);
});

test('pixels are drawn where the bodies are', async () => {
  await paused();
  const bodies = await page.evaluate(() => Array.from({ length: 16 }, (_, i) => window.ccdsim.bodyOnScreen(i)));
  // The cue ball (index 0) lies left of the rack (1–15); balls are a few pixels wide.
  for (let i = 1; i < 16; i++) assert.ok(bodies[0].x < bodies[i].x - 50, `ball ${i} right of the cue ball`);
  assert.ok(bodies[0].r > 3, `radius ${bodies[0].r} px`);
  for (const [i, b] of bodies.entries()) {
    const c = await pixel(b.x, b.y);
    assert.notDeepEqual(c, BACKGROUND, `body ${i} at (${b.x}, ${b.y}) is drawn`);
    // Its colour is its id's, as the PNG renderer draws it.
    const want = await page.evaluate((i) => Raster.idColour(Raster.idBucket(i)), i);
    assert.deepEqual(c, want, `colour of body ${i}`);
  }
  // Between the cue ball and the rack there is only cloth.
  const mid = { x: (bodies[0].x + bodies[1].x) / 2, y: bodies[0].y };
  assert.deepEqual(await pixel(mid.x, mid.y), BACKGROUND);
});

test('play advances the simulated time, a higher speed faster', async () => {
  await goTo(0.25);
  await setSpeed(-1); // 0.1×
  await page.click('#play');
  assert.equal(await page.evaluate(() => window.ccdsim.playing()), true);
  const slow = await simRate(800);
  await setSpeed(0); // 1×
  const fast = await simRate(800);
  await page.click('#play');
  assert.equal(await page.evaluate(() => window.ccdsim.playing()), false);
  assert.ok(slow > 0, `time advances at 0.1×: ${slow} s/s`);
  assert.ok(fast > 4 * slow, `1× (${fast} s/s) is much faster than 0.1× (${slow} s/s)`);
  assert.ok(fast < 1.5 && slow < 0.15, `rates follow the speed: ${slow}, ${fast}`);
  const applied = await page.evaluate(() => window.ccdsim.applied());
  assert.ok(applied > 0, 'events were applied while playing');
  assert.match(await page.textContent('#events'), new RegExp(`^event ${applied} / `));
});

test('toggling the boxes changes the picture', async () => {
  await goTo(0.4);
  const without = await canvasHash();
  assert.equal(await canvasHash(), without, 'a paused view is stable');
  await page.check('#boxes');
  await page.waitForFunction(() => {
    const b = window.ccdsim.boxes();
    return b.time === window.ccdsim.time() && (b.count > 0 || b.error);
  });
  const boxes = await page.evaluate(() => window.ccdsim.boxes());
  assert.equal(boxes.error, null, `boxes: ${boxes.error}`);
  // The BVH of 16 balls: 16 swept leaves and their inner nodes.
  assert.ok(boxes.count >= 31, `${boxes.count} boxes`);
  await frames(page);
  const withBoxes = await canvasHash();
  assert.notEqual(withBoxes, without);
  await page.screenshot({ path: path.join(OUT, 'viewer-boxes.png') });
  await page.uncheck('#boxes');
  await frames(page);
  assert.equal(await canvasHash(), without, 'boxes off: the picture is as before');
});

test('seeking to an event time shows the two bodies touching', async () => {
  const meta = await (await api('api/meta')).json();
  const ev = new Float64Array(await (await api('api/events?from=0&count=64')).arrayBuffer());
  const stride = 4 + 4 * meta.dim;
  let hit = null;
  for (let o = 0; o < ev.length; o += stride) {
    if (ev[o + 1] === 0) { hit = { t: ev[o], a: ev[o + 2], b: ev[o + 3] }; break; }
  }
  assert.ok(hit, 'the break has a ball–ball collision');
  await goTo(hit.t);
  const [A, B] = await page.evaluate(([a, b]) => [window.ccdsim.bodyOnScreen(a), window.ccdsim.bodyOnScreen(b)], [hit.a, hit.b]);
  const dist = Math.hypot(A.x - B.x, A.y - B.y);
  assert.ok(Math.abs(dist - (A.r + B.r)) < 0.01, `centres ${dist} px apart, radii sum ${A.r + B.r} px`);
  // No cloth between them along the line of centres, and both flash.
  for (let s = 0; s <= 1.0001; s += 1 / Math.ceil(dist)) {
    const c = await pixel(A.x + (B.x - A.x) * s, A.y + (B.y - A.y) * s);
    assert.notDeepEqual(c, BACKGROUND, `gap at ${s.toFixed(2)} of the way`);
  }
  assert.deepEqual(await pixel(A.x, A.y), FLASH_FILL);
  assert.deepEqual(await pixel(B.x, B.y), FLASH_FILL);
  const applied = await page.evaluate(() => window.ccdsim.applied());
  assert.ok(applied >= 1);
  await page.screenshot({ path: path.join(OUT, 'viewer.png') });
});

test('next and previous step from event to event', async () => {
  await goTo(0);
  await page.click('#next');
  await page.waitForFunction(() => window.ccdsim.applied() === 1);
  const t1 = await page.evaluate(() => window.ccdsim.time());
  await page.click('#next');
  await page.waitForFunction(() => window.ccdsim.applied() >= 2);
  const t2 = await page.evaluate(() => window.ccdsim.time());
  assert.ok(t2 > t1 && t1 > 0, `${t1} then ${t2}`);
  await page.click('#prev');
  await page.waitForFunction((t1) => window.ccdsim.time() === t1, t1);
  assert.equal(await page.evaluate(() => window.ccdsim.applied()), 1);
});
