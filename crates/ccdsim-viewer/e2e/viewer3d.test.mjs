// The viewer on a 3D run: an orthographic view of shaded spheres that orbits when dragged.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { frames, openViewer, pixelAt } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/debug/ccdsim');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const BACKGROUND = [17, 20, 24];
const N = 200;

let work, server, context, page;

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e3d-'));
  mkdirSync(OUT, { recursive: true });
  const scene = path.join(work, 'gas3d.json');
  writeFileSync(scene, execFileSync(BIN, ['gen', 'gas', '--dim', '3', '--n', String(N), '--seed', '3', '--speed-max', '2']));
  const run = path.join(work, 'gas3d.ccd');
  execFileSync(BIN, ['run', scene, '--until', '2', '--record', run, '--quiet']);
  ({ server, context, page } = await openViewer(BIN, run, path.join(work, 'profile'),
    (e) => { throw e; }));
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

const pixel = (x, y) => pixelAt(page, x, y);

const canvasHash = () =>
  page.evaluate(() => {
    const c = document.getElementById('view');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let h = 2166136261;
    for (let i = 0; i < d.length; i += 4) h = Math.imul(h ^ (d[i] | (d[i + 1] << 8) | (d[i + 2] << 16)), 16777619);
    return h >>> 0;
  });

test('a 3D run is drawn as an orthographic view of spheres', async () => {
  assert.match(await page.textContent('#status'), /orthographic view: drag to orbit/);
  await frames(page);
  const bodies = await page.evaluate((n) => Array.from({ length: n }, (_, i) => window.ccdsim.bodyOnScreen(i)), N);
  // Every centre is covered by its sphere or a nearer one.
  for (const [i, b] of bodies.entries()) {
    assert.notDeepEqual(await pixel(b.x, b.y), BACKGROUND, `body ${i} at (${b.x}, ${b.y})`);
  }
  // Orthographic: all spheres of one radius look the same size.
  const radii = new Set(bodies.map((b) => b.r.toFixed(6)));
  assert.equal(radii.size, 1, `one on-screen radius: ${[...radii]}`);
});

test('dragging orbits the camera', async () => {
  const before = await canvasHash();
  const p0 = await page.evaluate(() => window.ccdsim.bodyOnScreen(0));
  const box = await page.locator('#view').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 30, { steps: 6 });
  await page.mouse.up();
  await frames(page);
  const p1 = await page.evaluate(() => window.ccdsim.bodyOnScreen(0));
  assert.notEqual(await canvasHash(), before, 'the picture turned');
  assert.ok(Math.hypot(p1.x - p0.x, p1.y - p0.y) > 1, `body 0 moved on screen: ${JSON.stringify([p0, p1])}`);
  assert.equal(await page.evaluate(() => window.ccdsim.time()), 0, 'orbiting does not move time');
  await page.screenshot({ path: path.join(OUT, 'viewer-3d.png') });
});
