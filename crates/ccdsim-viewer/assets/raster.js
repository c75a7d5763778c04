// A small software rasteriser into one ImageData: the "batched canvas" the viewer draws
// with. Every body, wall and box of a frame is written straight into a Uint32Array and the
// frame reaches the canvas in one putImageData, so 10^5 bodies cost a few pixel writes each
// and the picture is the same with or without a GPU (headless browsers often have none).
//
// Colours are the renderer's (src/render/colour.rs): keep the two in step.
'use strict';

const Raster = (() => {
  const BUCKETS = 64;
  const BACKGROUND = [17, 20, 24];
  const WALL = [200, 200, 200];
  const LEAF_BOX = [120, 230, 140];
  const FLASH_FILL = [255, 255, 255];
  const FLASH_RING = [255, 210, 40];
  const SENSOR = [70, 150, 170];
  const SENSOR_HELD = [80, 240, 255];

  function hsv(h, s, v) {
    const i = Math.floor(h * 6);
    const f = h * 6 - i;
    const p = v * (1 - s), q = v * (1 - f * s), t = v * (1 - (1 - f) * s);
    const k = ((i % 6) + 6) % 6;
    const [r, g, b] = [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][k];
    return [Math.round(r * 255), Math.round(g * 255), Math.round(b * 255)];
  }

  const idBucket = (id) => Math.min(BUCKETS - 1, Math.floor(((id * 0.618033988749895) % 1) * BUCKETS));
  const speedBucket = (s, max) =>
    Math.min(BUCKETS - 1, Math.round((max > 0 ? Math.min(1, Math.max(0, s / max)) : 0) * (BUCKETS - 1)));
  const idColour = (b) => hsv(b / BUCKETS, 0.65, 0.95);
  function speedColour(b) {
    const stops = [[40, 60, 160], [40, 200, 220], [250, 230, 60], [240, 60, 40]];
    const s = (b / (BUCKETS - 1)) * 3;
    const k = Math.min(2, Math.floor(s));
    const f = s - k;
    return [0, 1, 2].map((c) => Math.round(stops[k][c] + (stops[k + 1][c] - stops[k][c]) * f));
  }
  const depthColour = (d) => hsv((d * 0.13 + 0.55) % 1, 0.8, 1.0);
  // Little-endian RGBA in one 32-bit word.
  const pack = ([r, g, b]) => ((255 << 24) | (b << 16) | (g << 8) | r) >>> 0;
  const ID_WORDS = Array.from({ length: BUCKETS }, (_, b) => pack(idColour(b)));
  const SPEED_WORDS = Array.from({ length: BUCKETS }, (_, b) => pack(speedColour(b)));
  const DEPTH_WORDS = Array.from({ length: 32 }, (_, d) => pack(depthColour(d)));

  class Surface {
    constructor(ctx, width, height) {
      this.ctx = ctx;
      this.w = width;
      this.h = height;
      this.image = ctx.createImageData(width, height);
      this.px = new Uint32Array(this.image.data.buffer);
      this.zbuf = null;
    }
    clear() {
      this.px.fill(pack(BACKGROUND));
      if (this.zbuf) this.zbuf.fill(-Infinity);
    }
    useDepth() {
      if (!this.zbuf) this.zbuf = new Float32Array(this.w * this.h);
      this.zbuf.fill(-Infinity);
    }
    present() {
      this.ctx.putImageData(this.image, 0, 0);
    }
    // A filled disc. Discs wider than a few pixels get anti-aliased left and right edges
    // (one blended pixel per side and row): smooth enough, and nearly free.
    disc(cx, cy, r, word) {
      const { w, h, px } = this;
      if (r < 0.75) r = 0.75;
      const aa = r >= 2;
      const y0 = Math.max(0, Math.ceil(cy - r - 0.5)), y1 = Math.min(h - 1, Math.floor(cy + r - 0.5));
      for (let y = y0; y <= y1; y++) {
        const dy = y + 0.5 - cy;
        const half = Math.sqrt(Math.max(0, r * r - dy * dy));
        const x0 = Math.max(0, Math.ceil(cx - half - 0.5)), x1 = Math.min(w - 1, Math.floor(cx + half - 0.5));
        if (x1 >= x0) px.fill(word, y * w + x0, y * w + x1 + 1);
        if (aa) {
          // Pixel centres outside the span, covered by the fraction the edge reaches in.
          const l = x0 - 1, fl = x0 - 0.5 - (cx - half);
          if (l >= 0 && fl > 0) px[y * w + l] = blend(px[y * w + l], word, Math.min(1, fl));
          const rr = x1 + 1, fr = cx + half - (x1 + 0.5);
          if (rr < w && fr > 0) px[y * w + rr] = blend(px[y * w + rr], word, Math.min(1, fr));
        }
      }
    }
    // A shaded sphere with depth test; z is the centre's depth in pixels (larger is nearer).
    sphere(cx, cy, z, r, rgb) {
      const { w, h, px, zbuf } = this;
      if (r < 0.75) r = 0.75;
      const y0 = Math.max(0, Math.ceil(cy - r - 0.5)), y1 = Math.min(h - 1, Math.floor(cy + r - 0.5));
      const inv = 1 / r;
      for (let y = y0; y <= y1; y++) {
        const dy = y + 0.5 - cy;
        const half = Math.sqrt(Math.max(0, r * r - dy * dy));
        const x0 = Math.max(0, Math.ceil(cx - half - 0.5)), x1 = Math.min(w - 1, Math.floor(cx + half - 0.5));
        for (let x = x0; x <= x1; x++) {
          const dx = x + 0.5 - cx;
          const nz2 = 1 - (dx * dx + dy * dy) * inv * inv;
          const nz = nz2 > 0 ? Math.sqrt(nz2) : 0;
          const depth = z + nz * r;
          const k = y * w + x;
          if (depth <= zbuf[k]) continue;
          zbuf[k] = depth;
          // Light from the upper left, in front.
          const l = Math.max(0, (-dx * inv) * 0.45 + (-dy * inv) * 0.45 + nz * 0.77);
          const s = 0.3 + 0.7 * l;
          px[k] = ((255 << 24) | (Math.min(255, rgb[2] * s) << 16) | (Math.min(255, rgb[1] * s) << 8) | Math.min(255, rgb[0] * s)) >>> 0;
        }
      }
    }
    // A ring between radii r0 and r1.
    ring(cx, cy, r0, r1, word) {
      const { w, h, px } = this;
      const y0 = Math.max(0, Math.ceil(cy - r1)), y1 = Math.min(h - 1, Math.floor(cy + r1));
      for (let y = y0; y <= y1; y++) {
        const dy = y + 0.5 - cy;
        for (let x = Math.max(0, Math.ceil(cx - r1)); x <= Math.min(w - 1, Math.floor(cx + r1)); x++) {
          const dx = x + 0.5 - cx;
          const d2 = dx * dx + dy * dy;
          if (d2 >= r0 * r0 && d2 <= r1 * r1) px[y * w + x] = word;
        }
      }
    }
    // A line (DDA, clipped to the surface), `thick` pixels wide (1 or 2).
    line(x0, y0, x1, y1, word, thick = 1) {
      const { w, h, px } = this;
      // Clip against a generous box first so that far-away end points cost nothing.
      const c = clip(x0, y0, x1, y1, -2, -2, w + 2, h + 2);
      if (!c) return;
      [x0, y0, x1, y1] = c;
      const n = Math.ceil(Math.max(Math.abs(x1 - x0), Math.abs(y1 - y0))) + 1;
      const sx = (x1 - x0) / n, sy = (y1 - y0) / n;
      let x = x0, y = y0;
      for (let i = 0; i <= n; i++, x += sx, y += sy) {
        const xi = Math.floor(x), yi = Math.floor(y);
        if (xi >= 0 && xi < w && yi >= 0 && yi < h) px[yi * w + xi] = word;
        if (thick > 1) {
          if (xi + 1 < w && xi + 1 >= 0 && yi >= 0 && yi < h) px[yi * w + xi + 1] = word;
          if (yi + 1 < h && yi + 1 >= 0 && xi >= 0 && xi < w) px[(yi + 1) * w + xi] = word;
        }
      }
    }
    rect(x0, y0, x1, y1, word) {
      this.line(x0, y0, x1, y0, word);
      this.line(x1, y0, x1, y1, word);
      this.line(x1, y1, x0, y1, word);
      this.line(x0, y1, x0, y0, word);
    }
    fillRect(x0, y0, x1, y1, word) {
      const { w, h, px } = this;
      x0 = Math.max(0, Math.floor(x0)); x1 = Math.min(w, Math.ceil(x1));
      y0 = Math.max(0, Math.floor(y0)); y1 = Math.min(h, Math.ceil(y1));
      for (let y = y0; y < y1; y++) if (x1 > x0) px.fill(word, y * w + x0, y * w + x1);
    }
  }

  // `over` laid on `under` with opacity a in [0, 1] (opaque words).
  function blend(under, over, a) {
    const mix = (s) => Math.round(((under >>> s) & 255) * (1 - a) + ((over >>> s) & 255) * a);
    return ((255 << 24) | (mix(16) << 16) | (mix(8) << 8) | mix(0)) >>> 0;
  }

  // Liang–Barsky clipping of a segment to a rectangle; null when it misses.
  function clip(x0, y0, x1, y1, xmin, ymin, xmax, ymax) {
    let t0 = 0, t1 = 1;
    const dx = x1 - x0, dy = y1 - y0;
    const p = [-dx, dx, -dy, dy], q = [x0 - xmin, xmax - x0, y0 - ymin, ymax - y0];
    for (let i = 0; i < 4; i++) {
      if (p[i] === 0) { if (q[i] < 0) return null; continue; }
      const r = q[i] / p[i];
      if (p[i] < 0) { if (r > t1) return null; if (r > t0) t0 = r; }
      else { if (r < t0) return null; if (r < t1) t1 = r; }
    }
    return [x0 + t0 * dx, y0 + t0 * dy, x0 + t1 * dx, y0 + t1 * dy];
  }

  return {
    Surface, pack, idBucket, speedBucket, idColour, speedColour, depthColour,
    ID_WORDS, SPEED_WORDS, DEPTH_WORDS, BACKGROUND, WALL, LEAF_BOX, FLASH_FILL, FLASH_RING,
    WALL_WORD: pack(WALL), LEAF_WORD: pack(LEAF_BOX), FLASH_FILL_WORD: pack(FLASH_FILL),
    FLASH_RING_WORD: pack(FLASH_RING), SENSOR_WORD: pack(SENSOR), SENSOR_HELD_WORD: pack(SENSOR_HELD),
  };
})();
