// The pool page: a recorded pool shot on its table, played at a chosen speed of time.
// Everything comes from /api/pool (crates/ccdsim-viewer/src/pool.rs): the table, the events
// with pooltool's names, and the balls sampled at a fixed rate, each with a marker fixed in
// the ball (drawn where it shows from above, with its antipode) that turns with its spin.
'use strict';

(() => {
  const canvas = document.getElementById('view');
  const ctx = canvas.getContext('2d');
  const el = (id) => document.getElementById(id);
  // Pool ball colours by number; 9–15 are the striped 1–7.
  const COLOURS = {
    1: '#f2c318', 2: '#1f47c7', 3: '#d1312b', 4: '#5e2a8c', 5: '#f07a14', 6: '#16804a',
    7: '#7a1f24', 8: '#141414',
  };
  const CLOTH = '#1d6b3a', RAIL = '#5a3a22', CUSHION = '#2f8a4f', POCKET = '#050505';
  const S = { data: null, time: 0, playing: false, speed: 1, last: null, drawn: 0,
    scale: 1, ox: 0, oy: 0 };

  // Table (x across, y along the long side) to canvas: the long side runs left to right,
  // a quarter turn that keeps the sense of rotation.
  const toScreen = (x, y) => [S.ox + y * S.scale, S.oy + x * S.scale];

  function layout() {
    const r = canvas.getBoundingClientRect();
    const dpr = window.devicePixelRatio || 1;
    canvas.width = Math.round(r.width * dpr);
    canvas.height = Math.round(r.height * dpr);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    if (!S.data) return;
    const t = S.data.table, margin = 0.12;
    const w = t.length + 2 * margin, h = t.width + 2 * margin;
    S.scale = Math.min(r.width / w, r.height / h);
    S.ox = (r.width - t.length * S.scale) / 2;
    S.oy = (r.height - t.width * S.scale) / 2;
  }

  function frameAt(t) {
    const d = S.data;
    const f = Math.min(d.count - 1, Math.max(0, t / d.dt));
    return [Math.floor(f), f - Math.floor(f)];
  }

  // Ball i at time t: position, marker and motion state, between the two nearest frames.
  function ballAt(i, t) {
    const d = S.data, n = d.names.length;
    const [f, u] = frameAt(t);
    const g = Math.min(f + 1, d.count - 1);
    const p = (k, stride, arr) => arr[f * n * stride + i * stride + k] * (1 - u)
      + arr[g * n * stride + i * stride + k] * u;
    const m = [p(0, 3, d.marker), p(1, 3, d.marker), p(2, 3, d.marker)];
    const len = Math.hypot(m[0], m[1], m[2]) || 1;
    return {
      x: p(0, 2, d.pos), y: p(1, 2, d.pos),
      marker: m.map((c) => c / len),
      state: d.state[f * n + i],
    };
  }

  function drawTable() {
    const t = S.data.table, s = S.scale;
    const [x0, y0] = toScreen(0, 0);
    const rail = 0.09 * s;
    ctx.fillStyle = RAIL;
    ctx.fillRect(x0 - rail, y0 - rail, t.length * s + 2 * rail, t.width * s + 2 * rail);
    ctx.fillStyle = CLOTH;
    ctx.fillRect(x0 - 0.035 * s, y0 - 0.035 * s, t.length * s + 0.07 * s, t.width * s + 0.07 * s);
    ctx.fillStyle = POCKET;
    for (const [x, y, r] of t.pockets) {
      const [sx, sy] = toScreen(x, y);
      ctx.beginPath(); ctx.arc(sx, sy, r * s, 0, 2 * Math.PI); ctx.fill();
    }
    ctx.strokeStyle = CUSHION;
    ctx.lineWidth = Math.max(1.5, 0.004 * s);
    ctx.lineCap = 'round';
    for (const [x1, y1, x2, y2] of t.cushions) {
      const [a, b] = toScreen(x1, y1), [c, d] = toScreen(x2, y2);
      ctx.beginPath(); ctx.moveTo(a, b); ctx.lineTo(c, d); ctx.stroke();
    }
    for (const [x, y, r] of t.jaws) {
      const [sx, sy] = toScreen(x, y);
      ctx.beginPath(); ctx.arc(sx, sy, r * s, 0, 2 * Math.PI); ctx.stroke();
    }
  }

  function drawBall(i, b) {
    const d = S.data, name = d.names[i], num = parseInt(name, 10);
    const r = d.radius * S.scale;
    const [sx, sy] = toScreen(b.x, b.y);
    const colour = name === 'cue' ? '#f4f1e6' : (COLOURS[num > 8 ? num - 8 : num] || '#c0c0c0');
    ctx.save();
    ctx.beginPath(); ctx.arc(sx, sy, r, 0, 2 * Math.PI);
    ctx.fillStyle = num > 8 ? '#f4f1e6' : colour;
    ctx.fill();
    if (num > 8) {
      ctx.clip();
      ctx.fillStyle = colour;
      ctx.fillRect(sx - r, sy - 0.55 * r, 2 * r, 1.1 * r);
    }
    ctx.restore();
    ctx.lineWidth = 1;
    ctx.strokeStyle = b.state === 2 ? '#ffffff' : 'rgba(0,0,0,0.6)'; // sliding: a white rim
    ctx.beginPath(); ctx.arc(sx, sy, r, 0, 2 * Math.PI); ctx.stroke();
    if (el('spin').checked) {
      // The marker or its antipode, whichever faces up; nearer the rim as it tips away.
      const m = b.marker[2] >= 0 ? b.marker : b.marker.map((c) => -c);
      const [mx, my] = [sx + m[1] * r, sy + m[0] * r];
      ctx.fillStyle = num === 8 || colour === COLOURS[2] || colour === COLOURS[4] ? '#ffffff' : '#101010';
      ctx.beginPath(); ctx.arc(mx, my, Math.max(1.2, 0.22 * r), 0, 2 * Math.PI); ctx.fill();
    }
    if (r > 7 && name !== 'cue') {
      ctx.fillStyle = num === 8 ? '#ffffff' : '#101010';
      ctx.font = `${Math.round(r * 0.8)}px system-ui, sans-serif`;
      ctx.textAlign = 'center'; ctx.textBaseline = 'middle';
      ctx.fillText(name, sx, sy);
    }
  }

  // An event's agents by role: "balls 1, 2", "ball 5, cushion 9", "ball 4".
  function agents(e) {
    const a = e.agents;
    switch (e.type) {
      case 'ball_ball': return `balls ${a[0]}, ${a[1]}`;
      case 'ball_linear_cushion': return `ball ${a[0]}, cushion ${a[1]}`;
      case 'ball_circular_cushion': return `ball ${a[0]}, jaw ${a[1]}`;
      case 'ball_pocket': return `ball ${a[0]}, pocket ${a[1]}`;
      default: return `ball ${a[0]}`;
    }
  }

  function lastEvent(t) {
    const ev = S.data.events;
    let lo = -1, hi = ev.length;
    while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (ev[mid].t <= t) lo = mid; else hi = mid; }
    return lo;
  }

  function draw() {
    const r = canvas.getBoundingClientRect();
    ctx.fillStyle = '#111418';
    ctx.fillRect(0, 0, r.width, r.height);
    if (!S.data) return;
    drawTable();
    const d = S.data;
    for (let i = 0; i < d.names.length; i++) {
      const gone = d.pocketed[i];
      if (gone !== null && gone <= S.time) continue;
      drawBall(i, ballAt(i, S.time));
    }
    el('time').textContent = `t = ${S.time.toFixed(3)} s / ${d.end.toFixed(3)} s`;
    el('seek').value = String(Math.round((S.time / Math.max(d.end, 1e-9)) * 100000));
    const k = lastEvent(S.time);
    el('event').textContent = k < 0 ? '—'
      : `event ${k + 1} / ${d.events.length}: ${d.events[k].type} (${agents(d.events[k])}) at ${d.events[k].t.toFixed(6)} s`;
    const down = d.names.filter((_, i) => d.pocketed[i] !== null && d.pocketed[i] <= S.time);
    el('pocketed').textContent = down.length ? `pocketed: ${down.join(', ')}` : '';
    S.drawn++;
  }

  function tick(now) {
    if (S.playing && S.data) {
      if (S.last !== null) S.time = Math.min(S.data.end, S.time + ((now - S.last) / 1000) * S.speed);
      S.last = now;
      if (S.time >= S.data.end) setPlaying(false);
    }
    draw();
    requestAnimationFrame(tick);
  }

  function setPlaying(on) {
    if (on && S.time >= S.data.end) S.time = 0;
    S.playing = on;
    S.last = null;
    el('play').textContent = on ? '❚❚ pause' : '▶ play';
  }

  async function start() {
    window.addEventListener('resize', layout);
    el('play').addEventListener('click', () => setPlaying(!S.playing));
    el('speed').addEventListener('change', () => { S.speed = parseFloat(el('speed').value); });
    el('seek').addEventListener('input', () => {
      S.time = (parseInt(el('seek').value, 10) / 100000) * S.data.end;
    });
    window.addEventListener('keydown', (e) => {
      if (e.code === 'Space' && e.target.tagName !== 'INPUT') { e.preventDefault(); setPlaying(!S.playing); }
    });
    const r = await fetch('/api/pool');
    if (!r.ok) { el('status').textContent = `cannot load the shot: ${(await r.json()).error}`; return; }
    S.data = await r.json();
    el('file').textContent = S.data.file;
    el('status').textContent = S.data.warning || `${S.data.names.length} balls, ${S.data.events.length} events`;
    if (!S.data.warning) el('status').classList.add('ok');
    layout();
    requestAnimationFrame(tick);
    window.ccdsim.ready = true;
  }

  // What the end-to-end tests read and set.
  window.ccdsim = {
    ready: false,
    frames: () => S.drawn,
    time: () => S.time,
    end: () => S.data.end,
    playing: () => S.playing,
    setTime: (t) => { S.time = t; },
    play: (on) => setPlaying(on),
    // Ball i's centre and radius on the canvas, in page pixels, and its marker's dot.
    ballOnScreen: (i) => {
      const b = ballAt(i, S.time);
      const [x, y] = toScreen(b.x, b.y);
      const m = b.marker[2] >= 0 ? b.marker : b.marker.map((c) => -c);
      const r = S.data.radius * S.scale;
      return { x, y, r, mx: x + m[1] * r, my: y + m[0] * r, state: b.state };
    },
    pocketOnScreen: (k) => {
      const [x, y, r] = S.data.table.pockets[k];
      const [sx, sy] = toScreen(x, y);
      return { x: sx, y: sy, r: r * S.scale };
    },
    data: () => S.data,
  };
  start();
})();
