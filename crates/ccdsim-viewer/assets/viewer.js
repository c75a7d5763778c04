// The ccdsim viewer page: streams a run from the server (snapshots to seek, windows of events
// to play) and draws it with the software rasteriser of raster.js.
//
// State is kept as the simulator keeps it: body i is at P[i] at time T0[i] and moves with
// V[i], so drawing at time t is P + V·(t − T0) and an event only rewrites its two bodies. In
// a run with gravity g (meta.gravity) bodies fall between events: P + V·dt + ½·g·dt², with
// velocity V + g·dt, dt = t − T0 (kinematic bodies do not fall).
//
// Arrays are per body slot, meta.bodies of them: a run that adds and removes bodies
// (meta.slot_edits) fills slots past the scene's and leaves removed bodies' slots vacant.
// A vacant slot has radius 0 and is not drawn. Snapshots of such a run carry every slot's
// radius, id and kinematic flag (src/wire.rs), and edit events update them as they play.
//
// In a run where bodies rest on walls (meta.rest_speed), each body falls or slides with an
// acceleration of its own, A[i]: g, or once a wall event's rest flag puts it on a plane or a
// segment, the acceleration it slides along it with (meta.slides[wall]), which a body event's
// flag keeps; any other event naming it without its flag makes it fall under g again (in
// format 12, a ball's wall event with the segment it slides on is its flight off the end). Snapshots carry
// every body's acceleration (src/wire.rs's rest section), events their rest flags.
//
// In such a run with 2D segments (format 13), a ball too slow to fly off a segment's end rolls
// over it: a wall event whose rest flags have bit 2 starts a turn of its body about the end
// point of the event's segment it reached, and the next event naming the body ends it.
// While it turns, the ball is drawn on its circle about that point, not on a parabola: its
// angle θ from "up" (−g) obeys θ̈ = (|g|/r)·sin θ, integrated here with RK4 in small steps
// from the turn's start (cached per body, so that playing forwards costs a few steps a frame).
// Snapshots carry the turns under way (src/wire.rs's pivot section).
//
// Moving walls (meta.moving_walls) are kept the same way: wall k is its scene geometry
// translated by WM's offset + velocity·(t − time); snapshots carry every wall's (time,
// offset, velocity) and edit events of code 5 restate one wall's (their `a` names the wall,
// not a body).
'use strict';

(() => {
  const $ = (id) => document.getElementById(id);
  const canvas = $('view');
  const ctx = canvas.getContext('2d');
  const WINDOW = 4096; // events per /api/events request
  const FLASH_MS = 350; // how long a colliding pair stays highlighted, wall milliseconds
  // In a dense run (a gas of 10^5 bodies) events come by the ten thousand per second: the
  // flash is shortened so that no more than this share of the bodies (or 6) is lit at once.
  const FLASH_SHARE = 0.02;
  const CATCH_UP_WALL = 0.25; // playback may lag the clock by this many wall seconds
  const SLOWMO_WALL = 0.4; // slow motion starts this many wall seconds from an event
  const STATE_HEADER = 8; // f64 values before a snapshot's arrays (src/wire.rs)
  const SLOT_SECTION = 1; // opens a snapshot's slot section (src/wire.rs)
  const WALL_SECTION = 2; // opens a snapshot's wall section (src/wire.rs)
  const REST_SECTION = 3; // opens a snapshot's rest section (src/wire.rs)
  const PIVOT_SECTION = 4; // opens a snapshot's pivot section (src/wire.rs)
  const PIVOT_A = 4; // bit of an event's rest flags: body a turns about a segment's end after it
  const PIVOT_STRIDE = 8; // f64s per turning body in the pivot section
  // RK4 steps of a turn, in units of the pendulum's time scale √(r/|g|).
  const TURN_STEP = 0.005;
  const EDIT = 3; // event kind of edits; their codes (b) as in crates/ccdsim/src/edit.rs:
  const ADD = 1, ADD_ID = 2, REMOVE = 3, WALL_MOTION = 5;

  const S = {
    meta: null, D: 2, n: 0, stride: 12,
    radius: null, ids: null, idBucket: null, kin: null, scene: null,
    P: null, V: null, T0: null, G: null, flash: null, evTime: null,
    A: null, slides: null, // resting runs only: per body acceleration; per static wall slide (or null)
    turns: null, // 2D resting runs only: per body its turn about a segment's end point, or null
    walls: [], WM: new Float64Array(0), // moving walls: scene geometry; per wall time, offset, velocity
    time: 0, applied: 0, lastEvent: null,
    buf: { start: 0, count: 0, data: new Float64Array(0) },
    fetching: false, seekToken: 0, seekBusy: false, seekWanted: null,
    playing: false, speed: 1, slowmo: false, colour: 'id',
    boxes: { on: false, data: null, time: NaN, busy: false, error: null, finder: '', sentAt: -Infinity, latencyMs: 0 },
    view: { zoom: 1, panX: 0, panY: 0, yaw: 35, pitch: 25 },
    surface: null, frames: 0, prevNow: null, error: null, seeking: false,
    window: WINDOW, eventRate: 0, flashMs: FLASH_MS, drawMs: 0, want: 0, seekMs: 50,
  };

  function setStatus(text, ok = false) {
    const el = $('status');
    el.textContent = text;
    el.className = ok ? 'ok' : '';
  }

  async function json(url) {
    const r = await fetch(url);
    const body = await r.json();
    if (!r.ok) throw new Error(body.error || `${url}: HTTP ${r.status}`);
    return body;
  }

  async function bin(url) {
    const r = await fetch(url);
    if (!r.ok) {
      let msg = `${url}: HTTP ${r.status}`;
      try { msg = (await r.json()).error || msg; } catch (_) { /* not JSON */ }
      throw new Error(msg);
    }
    return r.arrayBuffer();
  }

  // ---- the run's state ---------------------------------------------------------------

  function loadSnapshot(ab) {
    const h = new Float64Array(ab, 0, STATE_HEADER);
    const { D } = S;
    // The snapshot's slots: up to meta.bodies (a run that adds bodies has fewer earlier on).
    const n = h[2], m = Math.min(n, S.n);
    const pos = new Float32Array(ab, 8 * STATE_HEADER, n * D);
    const vel = new Float32Array(ab, 8 * STATE_HEADER + 4 * n * D, n * D);
    S.time = h[0];
    S.applied = h[1];
    S.P.set(pos.subarray(0, m * D));
    S.V.set(vel.subarray(0, m * D));
    S.T0.fill(S.time);
    const rests = loadRests(ab, loadWalls(ab, loadSlots(ab, 8 * STATE_HEADER + 8 * n * D, n, m)), n, m);
    loadTurns(ab, rests, m);
    S.lastEvent = h[4] >= 0 ? { t: h[5], kind: h[4], a: h[6], b: h[7] } : null;
    // Flashes of the events played before a jump mean nothing after it.
    S.flash.fill(-Infinity);
    S.evTime.fill(-Infinity);
    if (S.lastEvent) markEvent(S.lastEvent);
    S.buf = { start: S.applied, count: 0, data: new Float64Array(0) };
    S.fetching = false;
    // Landing exactly on an event (a step, or a seek to an event's time): flash its pair.
    if (S.lastEvent && S.lastEvent.t === S.time) flashEvent(S.lastEvent);
  }

  // The slots' radii, ids and kinematic flags: the snapshot's slot section from byte `off`
  // when it has one (bodies were added or removed by then), the scene's otherwise. Slots past
  // the snapshot's `n` hold no body yet. Returns the offset after the slot section.
  function loadSlots(ab, off, n, m) {
    const has = ab.byteLength >= off + 8 && new Float64Array(ab, off, 1)[0] === SLOT_SECTION;
    if (has) {
      const radius = new Float64Array(ab, off + 8, n);
      const ids = new Float64Array(ab, off + 8 + 8 * n, n);
      const flags = new Uint8Array(ab, off + 8 + 16 * n, n);
      for (let i = 0; i < m; i++) {
        S.radius[i] = radius[i];
        S.ids[i] = ids[i];
        S.idBucket[i] = Raster.idBucket(ids[i]);
        S.kin[i] = flags[i] & 1;
      }
    } else {
      S.radius.set(S.scene.radius);
      S.ids.set(S.scene.ids);
      S.idBucket.set(S.scene.idBucket);
      S.kin.set(S.scene.kin);
    }
    S.radius.fill(0, m);
    S.kin.fill(1, m);
    return has ? off + 8 + 17 * n : off;
  }

  // The moving walls' motions: the snapshot's wall section, which follows the slot section
  // from the next multiple of 8 bytes on (a run with moving walls always has one). Returns
  // the offset after it.
  function loadWalls(ab, off) {
    off = Math.ceil(off / 8) * 8;
    if (S.walls.length === 0 || ab.byteLength < off + 8 || new Float64Array(ab, off, 1)[0] !== WALL_SECTION) return off;
    S.WM.set(new Float64Array(ab, off + 8, S.WM.length));
    return off + 8 * (1 + S.WM.length);
  }

  // The bodies' accelerations in a run where bodies rest on walls: the snapshot's rest
  // section (n supports, then n·D accelerations), from the next multiple of 8 bytes on.
  // Returns the offset after it.
  function loadRests(ab, off, n, m) {
    if (!S.A) return off;
    off = Math.ceil(off / 8) * 8;
    const D = S.D;
    S.A.fill(0, m * D);
    if (ab.byteLength >= off + 8 * (1 + n + n * D) && new Float64Array(ab, off, 1)[0] === REST_SECTION) {
      S.A.set(new Float64Array(ab, off + 8 + 8 * n, n * D).subarray(0, m * D));
      return off + 8 * (1 + n + n * D);
    }
    for (let i = 0; i < m; i++) fall(i);
    return off;
  }

  // The turns under way at the snapshot: its pivot section (count, then per turning body
  // its slot, the point, the turn's start time, and its position and velocity then), from the
  // next multiple of 8 bytes after the rest section; no section, no body turns.
  function loadTurns(ab, off, m) {
    if (!S.turns) return;
    S.turns.fill(null);
    off = Math.ceil(off / 8) * 8;
    if (ab.byteLength < off + 16 || new Float64Array(ab, off, 1)[0] !== PIVOT_SECTION) return;
    const count = new Float64Array(ab, off + 8, 1)[0];
    const d = new Float64Array(ab, off + 16, count * PIVOT_STRIDE);
    for (let j = 0; j < count; j++) {
      const o = j * PIVOT_STRIDE, i = d[o];
      if (i < m) S.turns[i] = makeTurn(i, [d[o + 1], d[o + 2]], d[o + 3], [d[o + 4], d[o + 5]], [d[o + 6], d[o + 7]]);
    }
  }

  // The turn of body i about `point` from time t0, where it was at `pos` moving at `vel`: its
  // angle from up (−g, counter-clockwise towards `left`) and rate then, as ccdsim::motion::pivot's
  // Pivot::new takes them (the ball at its radius from the point); null where Pivot::new gives
  // no turn (no gravity, no radius), as the server then has none.
  function makeTurn(i, point, t0, pos, vel) {
    const G = S.G, g = G ? Math.hypot(G[0], G[1]) : 0, r = S.radius[i];
    if (!(g > 0 && Number.isFinite(g) && r > 0 && Number.isFinite(r))) return null;
    const up = [-G[0] / g, -G[1] / g], left = [G[1] / g, -G[0] / g];
    const d = [pos[0] - point[0], pos[1] - point[1]];
    const theta = Math.atan2(d[0] * left[0] + d[1] * left[1], d[0] * up[0] + d[1] * up[1]);
    const [s, c] = [Math.sin(theta), Math.cos(theta)];
    const rate = (vel[0] * (left[0] * c - up[0] * s) + vel[1] * (left[1] * c - up[1] * s)) / r;
    return { point, up, left, r, k: g / r, t0, theta0: theta, rate0: rate, t: t0, theta, rate };
  }

  // The angle and rate of turn `u` at time t (not before its start): θ̈ = k·sin θ, k = |g|/r,
  // by RK4 from the cached state when t is past it, else from the start.
  function turnAt(u, t) {
    if (t < u.t) { u.t = u.t0; u.theta = u.theta0; u.rate = u.rate0; }
    const k = u.k, hmax = TURN_STEP / Math.sqrt(k);
    let th = u.theta, w = u.rate, now = u.t;
    while (now < t) {
      const h = Math.min(hmax, t - now);
      const a1 = k * Math.sin(th);
      const w2 = w + 0.5 * h * a1, a2 = k * Math.sin(th + 0.5 * h * w);
      const w3 = w + 0.5 * h * a2, a3 = k * Math.sin(th + 0.5 * h * w2);
      const w4 = w + h * a3, a4 = k * Math.sin(th + h * w3);
      th += (h / 6) * (w + 2 * w2 + 2 * w3 + w4);
      w += (h / 6) * (a1 + 2 * a2 + 2 * a3 + a4);
      now = h === t - now ? t : now + h;
    }
    u.t = now; u.theta = th; u.rate = w;
    return u;
  }

  // Where turning body u is at time t, into `out`.
  function turnPosition(u, t, out) {
    const { theta } = turnAt(u, t), c = Math.cos(theta), s = Math.sin(theta);
    out[0] = u.point[0] + u.r * (c * u.up[0] + s * u.left[0]);
    out[1] = u.point[1] + u.r * (c * u.up[1] + s * u.left[1]);
    return out;
  }

  // Turning body u's speed at time t.
  const turnSpeed = (u, t) => u.r * Math.abs(turnAt(u, t).rate);

  // The end point of segment w (a static wall) that a body at p reached: as
  // ccdsim::contact::ledge::end_reached, the end nearer the foot of p.
  function endReached(w, p) {
    const u = [w.b[0] - w.a[0], w.b[1] - w.a[1]];
    const along = (p[0] - w.a[0]) * u[0] + (p[1] - w.a[1]) * u[1];
    return along >= 0.5 * (u[0] * u[0] + u[1] * u[1]) ? w.b.slice(0, 2) : w.a.slice(0, 2);
  }

  // Body i falls under g from now on (kinematic bodies and vacant slots do not fall).
  function fall(i) {
    const D = S.D;
    for (let k = 0; k < D; k++) S.A[i * D + k] = S.kin[i] || !S.G ? 0 : S.G[k];
  }

  // Body i slides along static wall w from now on.
  function slide(i, w) {
    const D = S.D, a = S.slides[w];
    for (let k = 0; k < D; k++) S.A[i * D + k] = a[k];
  }

  // A moving wall's edit names a wall, not a body: nothing to highlight.
  const namesBody = (e) => !(e.kind === EDIT && e.b === WALL_MOTION);

  // Remembers when each body last collided, so that a view paused at an event shows its pair
  // highlighted for as long as it stays there.
  function markEvent(e) {
    if (!namesBody(e)) return;
    S.evTime[e.a] = e.t;
    if (e.kind === 0) S.evTime[e.b] = e.t;
  }

  function flashEvent(e) {
    if (!namesBody(e)) return;
    const now = performance.now();
    S.flash[e.a] = now;
    if (e.kind === 0) S.flash[e.b] = now;
  }

  // Seeks to time t (seconds); concurrent calls collapse to the latest target. A catch-up
  // seek (while playing) leaves the clock running; any other one sets it to t.
  async function seek(t, catchUp = false) {
    S.seekWanted = t;
    if (!catchUp) S.want = t;
    if (S.seekBusy) return;
    S.seekBusy = true;
    try {
      while (S.seekWanted !== null) {
        const target = Math.min(Math.max(S.seekWanted, S.meta.start_time), S.meta.end_time);
        S.seekWanted = null;
        const token = ++S.seekToken;
        const t0 = performance.now();
        const ab = await bin(`/api/state?t=${target}`);
        S.seekMs = 0.5 * S.seekMs + 0.5 * (performance.now() - t0);
        if (token !== S.seekToken) continue;
        loadSnapshot(ab);
        if (S.want < S.time || !S.playing) S.want = S.time;
        fetchEvents();
      }
    } catch (e) {
      fail(e);
    } finally {
      S.seekBusy = false;
    }
  }

  async function fetchEvents() {
    const { buf, meta } = S;
    const from = buf.start + buf.count;
    if (S.fetching || from >= meta.events) return;
    S.fetching = true;
    const token = S.seekToken;
    try {
      const ab = await bin(`/api/events?from=${from}&count=${S.window}`);
      if (token !== S.seekToken) return;
      const fresh = new Float64Array(ab);
      // Keep only what is not applied yet.
      const drop = Math.max(0, Math.min(S.applied, from) - buf.start);
      const keep = buf.data.subarray(drop * S.stride, buf.count * S.stride);
      const data = new Float64Array(keep.length + fresh.length);
      data.set(keep);
      data.set(fresh, keep.length);
      S.buf = { start: buf.start + drop, count: buf.count - drop + fresh.length / S.stride, data };
    } catch (e) {
      fail(e);
    } finally {
      if (token === S.seekToken) S.fetching = false;
    }
  }

  // Offset in the buffer of event k, or −1 when it is not buffered.
  function eventOffset(k) {
    const { buf } = S;
    return k >= buf.start && k < buf.start + buf.count ? (k - buf.start) * S.stride : -1;
  }

  function applyEvent(o) {
    const d = S.buf.data, D = S.D;
    const t = d[o], kind = d[o + 1], a = d[o + 2], b = d[o + 3];
    const set = (i, p) => {
      for (let k = 0; k < D; k++) {
        S.P[i * D + k] = d[p + k];
        S.V[i * D + k] = d[p + D + k];
      }
      S.T0[i] = t;
      // Any event naming a turning body ends its turn (one that turns it starts another).
      if (S.turns) S.turns[i] = null;
    };
    S.lastEvent = { t, kind, a, b };
    S.applied++;
    if (kind === EDIT && b === ADD_ID) {
      // The id of the body just added: the bits of slot 1's first position component. No
      // state (slot 0 is zero).
      const bits = new DataView(d.buffer, d.byteOffset).getBigUint64(8 * (o + 4 + 2 * D), true);
      S.ids[a] = Number(bits);
      S.idBucket[a] = Raster.idBucket(S.ids[a]);
      return;
    }
    if (kind === EDIT && b === WALL_MOTION) {
      // Moving wall a from t on: slot 0 holds its offset then and its new velocity.
      const w = a * (1 + 2 * D);
      S.WM[w] = t;
      for (let k = 0; k < 2 * D; k++) S.WM[w + 1 + k] = d[o + 4 + k];
      return;
    }
    set(a, o + 4);
    if (kind === 0) set(b, o + 4 + 2 * D);
    if (kind === EDIT && b === ADD) {
      // Slot 1's position: radius, mass (Infinity for a kinematic body).
      S.radius[a] = d[o + 4 + 2 * D];
      S.kin[a] = d[o + 4 + 2 * D + 1] === Infinity ? 1 : 0;
    } else if (kind === EDIT && b === REMOVE) {
      S.radius[a] = 0;
      S.kin[a] = 1;
    }
    if (S.A) {
      // The event's rest flags: bit 0 body a rests on a wall after it, bit 1 body b does.
      const rests = d[o + 4 + 4 * D];
      if (kind === 1 && rests & 1) slide(a, b);
      else if (!(kind === 0 && rests & 1)) fall(a);
      if (kind === 0 && !(rests & 2)) fall(b);
      if (kind === 1 && rests & PIVOT_A && S.turns) {
        // Rolls over the end of segment b: turns about its end point, with no acceleration
        // of its own (as the server's rest section has it).
        const at = Array.from(d.subarray(o + 4, o + 6)), vel = Array.from(d.subarray(o + 6, o + 8));
        S.turns[a] = makeTurn(a, endReached(S.meta.walls[b], at), t, at, vel);
        if (S.turns[a]) S.A.fill(0, a * D, (a + 1) * D);
      }
    }
    markEvent(S.lastEvent);
    flashEvent(S.lastEvent);
  }

  // Moves the clock forward to `target`, applying the events on the way. Returns false when
  // the clock had to stop at the end of the buffered events.
  function advanceTo(target) {
    target = Math.min(target, S.meta.end_time);
    while (S.applied < S.meta.events) {
      const o = eventOffset(S.applied);
      if (o < 0) {
        // The next event is not here yet: it is no earlier than the last one applied.
        const known = S.lastEvent ? S.lastEvent.t : S.meta.start_time;
        S.time = Math.max(S.time, Math.min(target, known));
        // Starved: ask for bigger windows (the server caps them at 65536 events).
        if (!S.fetching) S.window = Math.min(65536, S.window * 2);
        fetchEvents();
        return false;
      }
      if (S.buf.data[o] > target) break;
      applyEvent(o);
    }
    S.time = target;
    if (S.buf.start + S.buf.count - S.applied < S.window / 2) fetchEvents();
    return true;
  }

  function slowFactor() {
    if (!S.slowmo) return 1;
    let dist = Infinity;
    const o = eventOffset(S.applied);
    if (o >= 0) dist = S.buf.data[o] - S.time;
    if (S.lastEvent) dist = Math.min(dist, S.time - S.lastEvent.t);
    return Math.min(1, Math.max(0.05, dist / S.speed / SLOWMO_WALL));
  }

  async function step(dir) {
    pause();
    try {
      if (dir > 0) {
        const o = eventOffset(S.applied);
        if (o >= 0 && S.buf.data[o] > S.time) { advanceTo(S.buf.data[o]); S.want = S.time; return; }
      }
      const r = await json(`/api/step?dir=${dir > 0 ? 'next' : 'prev'}&t=${S.time}`);
      if (r.time !== null) await seek(r.time);
    } catch (e) {
      fail(e);
    }
  }

  // ---- view --------------------------------------------------------------------------

  function rotation() {
    if (S.D === 2) return [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
    const y = (S.view.yaw * Math.PI) / 180, p = (S.view.pitch * Math.PI) / 180;
    const [sy, cy, sp, cp] = [Math.sin(y), Math.cos(y), Math.sin(p), Math.cos(p)];
    // Rx(pitch) · Ry(yaw), as the PNG renderer (src/render/camera.rs).
    return [[cy, 0, sy], [sp * sy, cp, -sp * cy], [-cp * sy, sp, cp * cy]];
  }

  // The transform from world to device pixels for the current canvas size and view.
  function makeCamera() {
    const { bounds } = S.meta;
    const D = S.D, R = rotation();
    const c = [0, 1, 2].map((k) => (k < D ? (bounds.min[k] + bounds.max[k]) / 2 : 0));
    const view = (p) => {
      const d = [p[0] - c[0], p[1] - c[1], D > 2 ? p[2] - c[2] : 0];
      return [0, 1, 2].map((i) => R[i][0] * d[0] + R[i][1] * d[1] + R[i][2] * d[2]);
    };
    let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    for (let corner = 0; corner < 1 << D; corner++) {
      const p = [];
      for (let k = 0; k < D; k++) p.push((corner >> k) & 1 ? bounds.max[k] : bounds.min[k]);
      const q = view(p);
      for (let k = 0; k < 2; k++) { lo[k] = Math.min(lo[k], q[k]); hi[k] = Math.max(hi[k], q[k]); }
    }
    const W = S.surface.w, H = S.surface.h, margin = 10;
    const fit = Math.min((W - 2 * margin) / Math.max(hi[0] - lo[0], 1e-12), (H - 2 * margin) / Math.max(hi[1] - lo[1], 1e-12));
    const scale = fit * S.view.zoom;
    const mid = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2];
    const ox = W / 2 + S.view.panX * dpr(), oy = H / 2 + S.view.panY * dpr();
    return {
      scale, R, c,
      project(x, y, z) {
        const d0 = x - c[0], d1 = y - c[1], d2 = D > 2 ? z - c[2] : 0;
        const q0 = R[0][0] * d0 + R[0][1] * d1 + R[0][2] * d2;
        const q1 = R[1][0] * d0 + R[1][1] * d1 + R[1][2] * d2;
        const q2 = R[2][0] * d0 + R[2][1] * d1 + R[2][2] * d2;
        return [ox + scale * (q0 - mid[0]), oy - scale * (q1 - mid[1]), scale * q2];
      },
      unproject2(sx, sy) {
        return [(sx - ox) / scale + mid[0] + c[0], -(sy - oy) / scale + mid[1] + c[1]];
      },
    };
  }

  const dpr = () => Math.min(2, window.devicePixelRatio || 1);

  function ensureSurface() {
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr()));
    const h = Math.max(1, Math.round(canvas.clientHeight * dpr()));
    if (!S.surface || S.surface.w !== w || S.surface.h !== h) {
      canvas.width = w;
      canvas.height = h;
      S.surface = new Raster.Surface(ctx, w, h);
    }
  }

  function position(i, t, out) {
    if (S.turns && S.turns[i]) return turnPosition(S.turns[i], t, out);
    const D = S.D, dt = t - S.T0[i], G = S.kin[i] ? null : S.G;
    for (let k = 0; k < D; k++) out[k] = S.P[i * D + k] + S.V[i * D + k] * dt;
    if (S.A) for (let k = 0; k < D; k++) out[k] += 0.5 * S.A[i * D + k] * dt * dt;
    else if (G) for (let k = 0; k < D; k++) out[k] += 0.5 * G[k] * dt * dt;
    return out;
  }

  // Body i's colour word at time t (its speed changes between events under gravity).
  function bodyWord(i, t) {
    if (S.colour === 'speed' && S.turns && S.turns[i]) {
      return Raster.SPEED_WORDS[Raster.speedBucket(turnSpeed(S.turns[i], t), S.meta.max_speed)];
    }
    if (S.colour === 'speed') {
      const D = S.D, G = S.kin[i] ? null : S.G, dt = t - S.T0[i];
      let v2 = 0;
      if (S.A) for (let k = 0; k < D; k++) v2 += (S.V[i * D + k] + S.A[i * D + k] * dt) ** 2;
      else for (let k = 0; k < D; k++) v2 += (S.V[i * D + k] + (G ? G[k] * dt : 0)) ** 2;
      return Raster.SPEED_WORDS[Raster.speedBucket(Math.sqrt(v2), S.meta.max_speed)];
    }
    return Raster.ID_WORDS[S.idBucket[i]];
  }

  function bodyRgb(i, t) {
    const w = bodyWord(i, t);
    return [w & 255, (w >>> 8) & 255, (w >>> 16) & 255];
  }

  // Moving wall k's displacement from its scene geometry at time t, into `out`.
  function wallOffset(k, t, out) {
    const D = S.D, w = k * (1 + 2 * D), dt = t - S.WM[w];
    for (let j = 0; j < D; j++) out[j] = S.WM[w + 1 + j] + S.WM[w + 1 + D + j] * dt;
    return out;
  }

  // Moving wall k where it is at time t: its scene geometry, translated.
  function movingWallAt(k, t) {
    const w = S.walls[k], off = wallOffset(k, t, [0, 0, 0]);
    const at = (p) => p.map((x, j) => x + off[j]);
    return w.a ? { a: at(w.a), b: at(w.b) } : { point: at(w.point), normal: w.normal };
  }

  // The static walls, and the moving walls where they are at time t. A 3D plane has no
  // edges: static ones are shown by the wire box of the run's bounds, and a moving one also
  // by the polygon where it cuts that box, so that it is seen to move.
  function drawWalls(cam, surf, t) {
    const D = S.D, { bounds } = S.meta;
    const span = Math.hypot(...bounds.max.map((x, k) => x - bounds.min[k])) || 1;
    let planes = false;
    const seg = (a, b) => {
      const p = cam.project(a[0], a[1], a[2]), q = cam.project(b[0], b[1], b[2]);
      surf.line(p[0], p[1], q[0], q[1], Raster.WALL_WORD, 2);
    };
    const draw = (w, moves) => {
      if (w.a) seg(w.a, w.b);
      else if (D === 2) {
        const len = Math.hypot(w.normal[0], w.normal[1]);
        const d = [(-w.normal[1] / len) * 10 * span, (w.normal[0] / len) * 10 * span];
        seg([w.point[0] - d[0], w.point[1] - d[1]], [w.point[0] + d[0], w.point[1] + d[1]]);
      } else {
        planes = true;
        if (moves) {
          const poly = planeSection(bounds, w.point, w.normal);
          for (let j = 0; j < poly.length; j++) seg(poly[j], poly[(j + 1) % poly.length]);
        }
      }
    };
    for (const w of S.meta.walls) draw(w, false);
    for (let k = 0; k < S.walls.length; k++) draw(movingWallAt(k, t), true);
    if (planes || (D === 3 && S.meta.walls.length === 0)) boxEdges(cam, surf, bounds.min, bounds.max, Raster.WALL_WORD);
  }

  // The corners of the polygon where a 3D plane cuts the box [min, max], in order around it
  // (as src/render/draw.rs's plane_section); none when it misses the box or only touches it.
  function planeSection({ min, max }, point, normal) {
    const side = (p) => normal[0] * (p[0] - point[0]) + normal[1] * (p[1] - point[1]) + normal[2] * (p[2] - point[2]);
    const corner = (c) => [0, 1, 2].map((k) => ((c >> k) & 1 ? max[k] : min[k]));
    const pts = [];
    for (let c = 0; c < 8; c++) {
      for (let k = 0; k < 3; k++) {
        if ((c >> k) & 1) continue;
        const p = corner(c), q = corner(c | (1 << k)), sp = side(p), sq = side(q);
        if (!((sp <= 0 && sq >= 0) || (sp >= 0 && sq <= 0))) continue;
        const f = sp === sq ? 0 : sp / (sp - sq);
        const x = p.map((v, j) => v + (q[j] - v) * f);
        // A plane through a corner meets its three edges there: one point.
        const tol = 1e-12 * (1 + Math.hypot(...x));
        if (!pts.some((y) => Math.hypot(y[0] - x[0], y[1] - x[1], y[2] - x[2]) <= tol)) pts.push(x);
      }
    }
    if (pts.length < 3) return [];
    const c = [0, 1, 2].map((j) => pts.reduce((s, p) => s + p[j], 0) / pts.length);
    const rel = (p) => p.map((v, j) => v - c[j]);
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const u = pts.map(rel).reduce((a, b) => (Math.hypot(...b) > Math.hypot(...a) ? b : a));
    const n = normal, v = [n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]];
    const angle = (p) => Math.atan2(dot(rel(p), v), dot(rel(p), u));
    return pts.sort((p, q) => angle(p) - angle(q));
  }

  // The scene's sensor regions as outlines, brighter while a body overlaps one (its centre
  // within the sum of the radii, the simulation's rule).
  function drawSensors(cam, surf, t) {
    const sensors = S.meta.sensors || [];
    if (sensors.length === 0) return;
    const D = S.D, p = [0, 0, 0];
    for (const s of sensors) {
      let held = false;
      for (let i = 0; i < S.n && !held; i++) {
        if (!(S.radius[i] > 0)) continue;
        position(i, t, p);
        let d2 = 0;
        for (let k = 0; k < D; k++) d2 += (p[k] - s.center[k]) ** 2;
        const reach = s.radius + S.radius[i];
        held = d2 < reach * reach;
      }
      const [x, y] = cam.project(s.center[0], s.center[1], D === 3 ? s.center[2] : 0);
      const r = s.radius * cam.scale;
      surf.ring(x, y, Math.max(0, r - 1.5 * dpr()), r, held ? Raster.SENSOR_HELD_WORD : Raster.SENSOR_WORD);
    }
  }

  function boxEdges(cam, surf, min, max, word) {
    const D = S.D;
    if (D === 2) {
      const a = cam.project(min[0], min[1]), b = cam.project(max[0], max[1]);
      surf.rect(a[0], a[1], b[0], b[1], word);
      return;
    }
    const pts = [];
    for (let c = 0; c < 8; c++) {
      pts.push(cam.project(c & 1 ? max[0] : min[0], c & 2 ? max[1] : min[1], c & 4 ? max[2] : min[2]));
    }
    for (let c = 0; c < 8; c++) {
      for (let k = 0; k < 3; k++) {
        if (!((c >> k) & 1)) {
          const a = pts[c], b = pts[c | (1 << k)];
          surf.line(a[0], a[1], b[0], b[1], word);
        }
      }
    }
  }

  function drawBoxes(cam, surf) {
    const data = S.boxes.data;
    if (!S.boxes.on || !data) return;
    const D = S.D, stride = 2 + 2 * D;
    const min = [0, 0, 0], max = [0, 0, 0];
    // Inner nodes first (by depth, as in the thesis's Figure 5.3), then the swept leaves.
    for (const leafPass of [0, 1]) {
      for (let o = 0; o < data.length; o += stride) {
        if (data[o + 1] !== leafPass) continue;
        for (let k = 0; k < D; k++) { min[k] = data[o + 2 + k]; max[k] = data[o + 2 + D + k]; }
        const word = leafPass ? Raster.LEAF_WORD : Raster.DEPTH_WORDS[data[o] % Raster.DEPTH_WORDS.length];
        boxEdges(cam, surf, min, max, word);
      }
    }
  }

  // Radii grow linearly in time in a growing run (settings.growth): their factor at `t`.
  function grown(t) {
    const g = S.meta.growth;
    return g ? 1 + g.rate * (t - g.origin) : 1;
  }

  function draw() {
    ensureSurface();
    const surf = S.surface, cam = makeCamera();
    S.camera = cam;
    const { n, D } = S, t = S.time, now = performance.now();
    const p = [0, 0, 0];
    surf.clear();
    drawWalls(cam, surf, t);
    drawSensors(cam, surf, t);
    const flashing = [];
    const lit = (i) => now - S.flash[i] < S.flashMs || (!S.playing && S.evTime[i] === t);
    // Vacant slots (radius 0) are neither drawn nor flashed.
    if (D === 2) {
      for (let i = 0; i < n; i++) {
        if (S.radius[i] === 0) continue;
        position(i, t, p);
        const [x, y] = cam.project(p[0], p[1]);
        const r = S.radius[i] * grown(t) * cam.scale;
        if (lit(i)) { flashing.push(i); continue; }
        surf.disc(x, y, r, bodyWord(i, t));
      }
    } else {
      surf.useDepth();
      for (let i = 0; i < n; i++) {
        if (S.radius[i] === 0) continue;
        position(i, t, p);
        const [x, y, z] = cam.project(p[0], p[1], p[2]);
        const r = S.radius[i] * grown(t) * cam.scale;
        const on = lit(i);
        if (on) flashing.push(i);
        surf.sphere(x, y, z, r, on ? Raster.FLASH_FILL : bodyRgb(i, t));
      }
    }
    drawBoxes(cam, surf);
    for (const i of flashing) {
      position(i, t, p);
      const [x, y] = cam.project(p[0], p[1], p[2]);
      const r = S.radius[i] * grown(t) * cam.scale;
      // In 2D a ring marks bodies big enough to see one around (tiny ones just turn white);
      // in 3D the white sphere alone, since a ring would show through nearer spheres.
      if (D === 2) {
        surf.disc(x, y, r, Raster.FLASH_FILL_WORD);
        if (r >= 2) surf.ring(x, y, r + 1.5 * dpr(), r + 4 * dpr(), Raster.FLASH_RING_WORD);
      }
    }
    // Progress along the run at the foot of the view.
    const span = S.meta.end_time - S.meta.start_time;
    if (span > 0) surf.fillRect(0, surf.h - 3, (surf.w * (t - S.meta.start_time)) / span, surf.h, Raster.pack([90, 140, 220]));
    surf.present();
    S.frames++;
  }

  // ---- boxes -------------------------------------------------------------------------

  // Asks for the boxes at the current time when they are stale. While playing, requests
  // are spaced by twice the last one's latency, so that a big run's boxes (a world rebuilt
  // and a BVH built on the server) never crowd out the events playback needs.
  async function refreshBoxes() {
    const B = S.boxes;
    if (!B.on || B.busy || (B.time === S.time && B.finder === finderName())) return;
    const now = performance.now();
    if (S.playing && now - B.sentAt < 2 * B.latencyMs) return;
    B.busy = true;
    B.sentAt = now;
    const t = S.time, finder = finderName();
    try {
      const ab = await bin(`/api/boxes?t=${t}&finder=${encodeURIComponent(finder)}`);
      B.data = new Float32Array(ab);
      B.error = null;
      const count = B.data.length / (2 + 2 * S.D);
      $('hint').textContent = `${count} boxes from ${finder} at t = ${t.toPrecision(6)} s`;
      if (count === 0) $('hint').textContent += ` (${finder} has no spatial structure to show)`;
    } catch (e) {
      B.data = null;
      B.error = e.message;
      $('hint').textContent = `boxes: ${e.message}`;
    } finally {
      B.latencyMs = performance.now() - B.sentAt;
      B.time = t;
      B.finder = finder;
      B.busy = false;
    }
  }

  const finderName = () => $('finder').value.trim() || S.meta.finder;

  // ---- controls ----------------------------------------------------------------------

  function play() {
    if (S.time >= S.meta.end_time) seek(S.meta.start_time);
    S.playing = true;
    S.want = S.time;
    $('play').textContent = '■ pause';
  }

  function pause() {
    S.playing = false;
    S.want = S.time;
    $('play').textContent = '▶ play';
  }

  function fail(e) {
    S.error = e.message || String(e);
    setStatus(S.error);
  }

  function updateLabels() {
    const { meta } = S;
    $('time').textContent = `t = ${S.time.toFixed(6)} s`;
    $('events').textContent = `event ${S.applied} / ${meta.events}`;
    if (!S.seeking) {
      const span = meta.end_time - meta.start_time;
      $('seek').value = span > 0 ? Math.round(((S.time - meta.start_time) / span) * 100000) : 0;
    }
  }

  function bindControls() {
    $('play').onclick = () => (S.playing ? pause() : play());
    $('next').onclick = () => step(1);
    $('prev').onclick = () => step(-1);
    const seekBar = $('seek');
    const seekTo = () => {
      const span = S.meta.end_time - S.meta.start_time;
      seek(S.meta.start_time + (seekBar.value / 100000) * span);
    };
    seekBar.addEventListener('input', () => { S.seeking = true; seekTo(); });
    seekBar.addEventListener('change', () => { S.seeking = false; seekTo(); });
    const speed = $('speed');
    const setSpeed = () => {
      S.speed = 10 ** Number(speed.value);
      $('speed-label').textContent = `${S.speed < 0.1 ? S.speed.toFixed(3) : S.speed.toFixed(2)}×`;
    };
    speed.addEventListener('input', setSpeed);
    setSpeed();
    $('slowmo').onchange = (e) => { S.slowmo = e.target.checked; };
    $('colour').onchange = (e) => { S.colour = e.target.value; };
    $('boxes').onchange = (e) => {
      S.boxes.on = e.target.checked;
      S.boxes.time = NaN;
      if (!S.boxes.on) $('hint').textContent = '';
    };
    $('finder').onchange = () => { S.boxes.time = NaN; };
    // Typing a time (e.g. an event's, as `ccdsim export` prints it) seeks there exactly.
    $('goto').addEventListener('keydown', (e) => {
      if (e.key !== 'Enter') return;
      const t = Number(e.target.value);
      if (e.target.value.trim() === '' || !Number.isFinite(t)) { setStatus(`go to: \`${e.target.value}\` is not a time`); return; }
      pause();
      seek(t);
    });
    window.addEventListener('keydown', (e) => {
      if (e.target.tagName === 'INPUT' && e.target.type === 'text') return;
      if (e.key === ' ') { e.preventDefault(); S.playing ? pause() : play(); }
      else if (e.key === 'ArrowRight') step(1);
      else if (e.key === 'ArrowLeft') step(-1);
    });
    // Drag pans (2D) or orbits (3D); the wheel zooms; a double click resets the view.
    let drag = null;
    canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY }; canvas.setPointerCapture(e.pointerId); });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag = { x: e.clientX, y: e.clientY };
      if (S.D === 2) { S.view.panX += dx; S.view.panY += dy; }
      else {
        S.view.yaw += dx * 0.4;
        S.view.pitch = Math.max(-89, Math.min(89, S.view.pitch + dy * 0.4));
      }
    });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const f = Math.exp(-e.deltaY * 0.0015);
      const rect = canvas.getBoundingClientRect();
      // Zoom about the cursor: keep the point under it fixed.
      const mx = e.clientX - rect.left - rect.width / 2, my = e.clientY - rect.top - rect.height / 2;
      S.view.panX = mx - (mx - S.view.panX) * f;
      S.view.panY = my - (my - S.view.panY) * f;
      S.view.zoom *= f;
    }, { passive: false });
    canvas.addEventListener('dblclick', () => { S.view = { zoom: 1, panX: 0, panY: 0, yaw: 35, pitch: 25 }; });
  }

  function frame(now) {
    const dt = S.prevNow === null ? 0 : Math.min(0.1, (now - S.prevNow) / 1000);
    S.prevNow = now;
    if (S.playing) {
      // `want` is where the clock should be; `time` follows it as far as the events at hand
      // allow. When events arrive slower than the clock needs them (a dense run at high
      // speed), a snapshot jumps ahead to where the clock will be when it arrives.
      const before = S.time, applied0 = S.applied;
      S.want = Math.min(S.meta.end_time, S.want + dt * S.speed * slowFactor());
      if (!S.seekBusy) advanceTo(S.want);
      if (!S.seekBusy && S.want - S.time > CATCH_UP_WALL * S.speed) {
        seek(Math.min(S.meta.end_time, S.want + (S.speed * S.seekMs) / 1000), true);
      }
      if (S.time >= S.meta.end_time && before < S.meta.end_time) pause();
      if (dt > 0) {
        S.eventRate = 0.9 * S.eventRate + 0.1 * ((S.applied - applied0) / dt);
        const lit = Math.max(6, FLASH_SHARE * S.n);
        S.flashMs = Math.min(FLASH_MS, (1000 * lit) / Math.max(1, 2 * S.eventRate));
      }
    }
    const d0 = performance.now();
    draw();
    S.drawMs = 0.9 * S.drawMs + 0.1 * (performance.now() - d0);
    updateLabels();
    refreshBoxes();
    requestAnimationFrame(frame);
  }

  async function start() {
    try {
      const meta = await json('/api/meta');
      S.meta = meta;
      S.D = meta.dim;
      S.n = meta.bodies;
      S.G = meta.gravity || null;
      // Resting runs: each event ends with its rest flags, each body has its acceleration.
      const resting = meta.rest_speed !== undefined;
      S.stride = 4 + 4 * meta.dim + (resting ? 1 : 0);
      S.slides = resting ? meta.slides : null;
      // Before the first snapshot's wall section: at their scene geometry and velocity.
      S.walls = meta.moving_walls || [];
      S.WM = new Float64Array(S.walls.length * (1 + 2 * S.D));
      S.walls.forEach((w, k) => {
        S.WM[k * (1 + 2 * S.D)] = meta.start_time;
        for (let j = 0; j < S.D; j++) S.WM[k * (1 + 2 * S.D) + 1 + S.D + j] = w.velocity[j];
      });
      // Kinematic bodies (by slot) move in straight lines: gravity does not move them.
      const kin = new Uint8Array(S.n);
      for (const i of meta.kinematic || []) kin[i] = 1;
      // The scene's radii and ids (padded to the slots with radius 0): snapshots without a
      // slot section have these; the page's own copies change as bodies are added and removed.
      const bodies = new Float64Array(await bin('/api/bodies'));
      const radius = bodies.slice(0, S.n), ids = bodies.slice(S.n, 2 * S.n);
      S.scene = { radius, ids, idBucket: Uint8Array.from(ids, Raster.idBucket), kin };
      S.radius = radius.slice();
      S.ids = ids.slice();
      S.idBucket = S.scene.idBucket.slice();
      S.kin = kin.slice();
      S.P = new Float64Array(S.n * S.D);
      S.V = new Float64Array(S.n * S.D);
      S.T0 = new Float64Array(S.n);
      S.A = resting ? new Float64Array(S.n * S.D) : null;
      S.turns = resting && S.D === 2 ? new Array(S.n).fill(null) : null;
      S.flash = new Float64Array(S.n).fill(-Infinity);
      S.evTime = new Float64Array(S.n).fill(-Infinity);
      const bodyCount = meta.slot_edits ? `${meta.scene_bodies} bodies at the start, bodies added and removed (${meta.bodies} slots)` : `${meta.bodies} bodies`;
      $('file').textContent = `${meta.file} · ${meta.dim}D · ${bodyCount} · ${meta.events} events${meta.complete ? '' : ' (no end record)'}`;
      $('finder').value = meta.finder;
      bindControls();
      await seek(meta.start_time);
      setStatus(meta.dim === 3 ? 'orthographic view: drag to orbit, wheel to zoom' : 'top-down view: drag to pan, wheel to zoom', true);
      requestAnimationFrame(frame);
      window.ccdsim.ready = true;
    } catch (e) {
      fail(e);
    }
  }

  // A small window into the page for tests and the curious console user.
  window.ccdsim = {
    ready: false,
    time: () => S.time,
    applied: () => S.applied,
    playing: () => S.playing,
    speed: () => S.speed,
    frames: () => S.frames,
    drawMs: () => S.drawMs,
    error: () => S.error,
    boxes: () => ({ on: S.boxes.on, count: S.boxes.data ? S.boxes.data.length / (2 + 2 * S.D) : 0, time: S.boxes.time, error: S.boxes.error }),
    seek: (t) => seek(t),
    // Slot i as the page holds it: radius (0 when vacant), id and kinematic flag.
    slot: (i) => ({ radius: S.radius[i], id: S.ids[i], kinematic: S.kin[i] === 1 }),
    // Body i's acceleration as the page holds it (a resting run), or null.
    acceleration: (i) => (S.A ? Array.from(S.A.subarray(i * S.D, (i + 1) * S.D)) : null),
    // Body i's position at the current time as the page draws it (metres, f64).
    position: (i) => position(i, S.time, [0, 0, 0]).slice(0, S.D),
    // Body i's turn about a segment's end point as the page holds it, or null.
    turn(i) {
      const u = S.turns && S.turns[i];
      return u ? { point: u.point.slice(), start: u.t0, theta0: u.theta0, rate0: u.rate0 } : null;
    },
    // Sensor k's centre and radius, in CSS pixels from the canvas's top-left corner.
    sensorOnScreen(k) {
      const s = S.meta.sensors[k];
      const [x, y] = S.camera.project(s.center[0], s.center[1], S.D === 3 ? s.center[2] : 0);
      return { x: x / dpr(), y: y / dpr(), r: (s.radius * S.camera.scale) / dpr() };
    },
    // The world point p ([x, y] or [x, y, z], metres) in CSS pixels from the canvas's
    // top-left corner.
    onScreen(p) {
      const [x, y] = S.camera.project(p[0], p[1], S.D === 3 ? p[2] : 0);
      return { x: x / dpr(), y: y / dpr() };
    },
    // Moving wall k at the current time: its displacement from its scene geometry (metres),
    // and its end points (a segment) or its point (a plane) in CSS pixels.
    movingWall(k) {
      const w = movingWallAt(k, S.time);
      const offset = wallOffset(k, S.time, [0, 0, 0]).slice(0, S.D);
      const on = window.ccdsim.onScreen;
      return w.a ? { offset, a: on(w.a), b: on(w.b) } : { offset, point: on(w.point) };
    },
    // Body i at the current time, in CSS pixels from the canvas's top-left corner (r is 0 for
    // a vacant slot, which is not drawn).
    bodyOnScreen(i) {
      const p = position(i, S.time, [0, 0, 0]);
      const [x, y] = S.camera.project(p[0], p[1], p[2]);
      return { x: x / dpr(), y: y / dpr(), r: (S.radius[i] * grown(S.time) * S.camera.scale) / dpr() };
    },
  };

  start();
})();
