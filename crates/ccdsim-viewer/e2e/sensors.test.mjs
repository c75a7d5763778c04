// The viewer on a run with sensors: a Galton board from `ccdsim gen pegs --bins`, whose bins
// along the floor are sensor regions. The page outlines each region, brighter while a ball is
// in it. Run through ./run.sh, which builds the binary; or set CCDSIM_BIN.

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { openViewer, pixelAt, goTo as goToOn } from './browser.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const BIN = process.env.CCDSIM_BIN || path.resolve(here, '../../../target/debug/ccdsim');
const OUT = process.env.E2E_OUT || path.join(here, 'out');
const SENSOR = [70, 150, 170]; // src/render/colour.rs, assets/raster.js
const SENSOR_HELD = [80, 240, 255];

let work, server, context, page, scene, sensorLog;
const pageErrors = [];

before(async () => {
  work = mkdtempSync(path.join(tmpdir(), 'ccdsim-e2e-sensors-'));
  mkdirSync(OUT, { recursive: true });
  const sceneFile = path.join(work, 'galton.json');
  const run = path.join(work, 'galton.ccd');
  const log = path.join(work, 'bins.jsonl');
  execFileSync(BIN, ['gen', 'pegs', '--rows', '4', '--balls', '24', '--bins', '4',
    '--restitution', '0.6', '--out', sceneFile]);
  execFileSync(BIN, ['run', sceneFile, '--until', '8', '--record', run, '--sensor-log', log,
    '--quiet']);
  scene = JSON.parse(readFileSync(sceneFile, 'utf8'));
  sensorLog = readFileSync(log, 'utf8').trim().split('\n')
    .filter((l) => l).map((l) => JSON.parse(l));
  ({ server, context, page } = await openViewer(BIN, run, path.join(work, 'profile'),
    (e) => pageErrors.push(e.message)));
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill();
  if (work) rmSync(work, { recursive: true, force: true });
});

const pixel = (x, y) => pixelAt(page, x, y);

const goTo = (t) => goToOn(page, t);

// Which sensors hold a ball at time t, from the run's sensor log (enters and leaves).
function heldAt(t) {
  const inside = scene.sensors.map(() => new Set());
  for (const e of sensorLog) {
    if (e.t > t) break;
    if (e.change === 'enter') inside[e.sensor].add(e.body);
    else inside[e.sensor].delete(e.body);
  }
  return inside.map((s) => s.size > 0);
}

test('every sensor region is outlined, brighter while a ball is in it', async () => {
  assert.ok(scene.sensors.length === 4, 'the scene has its four bins');
  assert.ok(sensorLog.some((e) => e.change === 'enter'), 'balls land in the bins');
  for (const t of [0.05, 7.5]) {
    await goTo(t);
    const held = heldAt(t);
    for (let k = 0; k < scene.sensors.length; k++) {
      const s = await page.evaluate((k) => window.ccdsim.sensorOnScreen(k), k);
      // The ring's top, three quarters of a pixel inside the outer edge of its 1.5 px
      // stroke (so that the pixel's centre lies on the stroke wherever the centre falls).
      const c = await pixel(s.x, s.y - s.r + 0.75);
      assert.deepEqual(c, held[k] ? SENSOR_HELD : SENSOR, `sensor ${k} at t = ${t}`);
    }
  }
  await page.screenshot({ path: path.join(OUT, 'sensors.png') });
  assert.deepEqual(pageErrors, []);
});
