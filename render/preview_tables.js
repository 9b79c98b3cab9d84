// The preview page's ports of the C++ it must agree with bit for bit: SplitMix64, derive_seed and
// the seeded permutation tables (base/random.hpp, tiling/lattice_hash.hpp), the tiles method's
// look-up textures, FNV-1a (base/hash.hpp) and the view's rows (render/view.hpp). `texture
// preview` embeds this file, then render/preview.js, in every page (render/preview.cpp); under
// node, tests/render/preview_golden.test.js loads it and checks it against the golden vectors
// (tests/render/preview_golden.json) that tests/render/test_preview_golden.cpp checks the C++ against.
'use strict';

// SplitMix64, derive_seed and the seeded permutation tables (base/random.hpp, tiling/lattice_hash.hpp).
const M64 = (1n << 64n) - 1n;
function mix(x) {
  x = (x + 0x9e3779b97f4a7c15n) & M64;
  x = ((x ^ (x >> 30n)) * 0xbf58476d1ce4e5b9n) & M64;
  x = ((x ^ (x >> 27n)) * 0x94d049bb133111ebn) & M64;
  return x ^ (x >> 31n);
}
class Rng {
  constructor(seed) { this.s = seed & M64; }
  next() { const z = this.s; this.s = (this.s + 0x9e3779b97f4a7c15n) & M64; return mix(z); }
  below(n) {  // Lemire's multiply-shift with rejection
    const N = BigInt(n), threshold = ((1n << 64n) - N) % N;
    for (;;) { const m = this.next() * N, low = m & M64; if (low >= N || low >= threshold) return Number(m >> 64n); }
  }
}
function derive(seed, stream) {
  const g = new Rng(seed ^ ((BigInt(stream) * 0xd1b54a32d192ed03n) & M64));
  g.next();
  return g.next();
}
function permutation(n, seed) {
  const r = new Rng(seed), p = Array.from({length: n}, (_, i) => i);
  for (let i = 0; i + 1 < n; ++i) { const j = i + r.below(n - i); const t = p[i]; p[i] = p[j]; p[j] = t; }
  return p;
}
function hashTable(recipe, seed) {
  let s = seed, all = [];
  for (const stream of recipe.streams) s = derive(s, stream);
  if (recipe.kind === 'perm') all = permutation(recipe.sizes[0], s);
  else recipe.sizes.forEach((n, i) => { all = all.concat(permutation(n, derive(s, i))); });
  while (all.length % 4) all.push(0);
  return new Int32Array(all);
}

// The tiles method's look-up textures for a seed (render/glsl_sampler.hpp, glsl_table_textures),
// from the seeded tables: with the permutation hash the atlas cell (row, col) of every tile of one
// period (the tiling of tiling/direct_tiling.hpp); with the long-period hash each hash's tables over
// one period, a texel holding a table's values mod C at a lattice point and its E, S, SE neighbours.
function tilingTextures(t, seed) {
  const C = t.colors, hashes = t.tables.map(r => ({sizes: r.sizes, p: hashTable(r, seed)}));
  if (t.positions) {
    const n = hashes[0].sizes[0], data = new Uint8Array(2 * n * n);
    const corners = (h, x, y) => {  // NW, NE, SW, SE
      const p = hashes[h].p, c = (a, b) => p[(p[a % n] + b % n) % n] % C;
      return [c(x, y), c(x + 1, y), c(x, y + 1), c(x + 1, y + 1)];
    };
    for (let y = 0; y < n; ++y) {
      for (let x = 0; x < n; ++x) {
        let tile;
        if (t.kind === 'corner') {  // thesis eq. (2.5)
          const [nw, ne, sw, se] = corners(0, x, y);
          tile = ((ne * C + se) * C + sw) * C + nw;
        } else {  // two hashes, each edge the sum of its end points (thesis 3.3.2.1, eq. 2.2)
          const h = corners(0, x, y), v = corners(1, x, y);
          tile = ((((h[0] + h[1]) % C) * C + (v[1] + v[3]) % C) * C + (h[3] + h[2]) % C) * C + (v[2] + v[0]) % C;
        }
        data.set(t.positions[tile], 2 * (y * n + x));
      }
    }
    return [{sampler: 'tk_tiles', unit: 3, width: n, height: n, channels: 2, data}];
  }
  return hashes.map((h, k) => {
    const width = h.sizes.reduce((a, b) => a + b, 0), height = Math.max(...h.sizes), data = new Uint8Array(4 * width * height);
    let o = 0;
    for (const n of h.sizes) {
      const c = (a, b) => h.p[o + (h.p[o + a % n] + b % n) % n] % C;
      for (let b = 0; b < n; ++b)
        for (let a = 0; a < n; ++a) data.set([c(a, b), c(a + 1, b), c(a, b + 1), c(a + 1, b + 1)], 4 * (b * width + o + a));
      o += n;
    }
    return {sampler: 'tk_lattice' + k + '_T', unit: 3 + k, width, height, channels: 4, data};
  });
}
function fnv(bytes) {  // FNV-1a 64 (base/hash.hpp)
  let h = 0xcbf29ce484222325n;
  for (const b of bytes) h = ((h ^ BigInt(b)) * 0x100000001b3n) & M64;
  return h.toString();
}

// The view's rows in fixed point (render/view.hpp, view_rows), the same double arithmetic.
function fixed(v) {
  let tile = Math.floor(v), frac = Math.round((v - tile) * 65536);
  if (frac >= 65536) { tile += 1; frac = 0; }
  return [tile, frac];
}
function viewRows(W, H, scale, ou, ov, tilt, unit) {
  if (!(scale > 0) || !(tilt >= 0 && tilt <= 100) || !isFinite(ou) || !isFinite(ov)) throw new Error('scale must be positive, tilt 0..100');
  const s = scale / unit, t = tilt, u0 = ou / unit, v0 = ov / unit;
  const rows = new Int32Array(8 * H), bits = new Float32Array(rows.buffer);
  for (let j = 0; j < H; ++j) {
    const yc = j + 0.5, q = 1 + t * (1 - yc / H);
    const step = s * q, first = u0 + W / 2 * s + (0.5 - W / 2) * step;
    const vv = v0 + s * (t === 0 ? yc : H / (3 * t) * ((1 + t) * (1 + t) * (1 + t) - q * q * q));
    if (step * 65536 >= 2 * 65536) throw new Error('the view moves 2 or more tiles per pixel: zoom in or tilt less');
    const [tu, fu] = fixed(first), [tv, fv] = fixed(vv);
    rows.set([tu, fu, Math.round(step * 65536), tv, fv], 8 * j);
    bits[8 * j + 5] = step;
    bits[8 * j + 6] = s * q * q;
    bits[8 * j + 7] = (0.5 - W / 2) * -s * t / H;
  }
  return {rows, dudyStep: Math.fround(-s * t / H)};
}

// Under node (the golden test) the ports are a module; in the page they are the script's own names.
if (typeof module !== 'undefined') module.exports = {mix, Rng, derive, permutation, hashTable, tilingTextures, fnv, fixed, viewRows};
