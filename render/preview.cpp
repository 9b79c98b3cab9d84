#include "render/preview.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string_view>

#include "base/hash.hpp"
#include "render/baseline_samplers.hpp"
#include "render/glsl_sampler.hpp"

namespace tilekit {

namespace {

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t a = std::uint8_t(bytes[i]), b = i + 1 < bytes.size() ? std::uint8_t(bytes[i + 1]) : 0,
                        c = i + 2 < bytes.size() ? std::uint8_t(bytes[i + 2]) : 0, v = a << 16 | b << 8 | c;
    out += kDigits[v >> 18];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// The half floats of a float image (as the GPU renderer uploads them), little-endian, base64.
std::string half_base64(const FloatImage& f) {
  std::string bytes;
  bytes.reserve(f.texels.size() * 2);
  for (float v : f.texels) {
    const std::uint16_t h = float_to_half(v);
    bytes += char(h & 255);
    bytes += char(h >> 8);
  }
  return base64(bytes);
}

// How the page recomputes a uniform hash table for any seed: the hash's seed is the page's seed
// passed through derive_seed with `streams` (DirectWangTiling and PatchHashes derive streams 1 and
// 2, DirectCornerTiling none); one permutation table (perm) or one per size with seed
// derive_seed(hash seed, i) (long-period, LongPeriodHash).
nlohmann::json recipe(const std::string& name, const ColourHash& h, std::vector<int> streams) {
  nlohmann::json sizes = nlohmann::json::array();
  for (const ColourHash::Component& c : h.components()) sizes.push_back(c.n);
  return {{"name", name}, {"kind", hash_kind_name(h.kind())}, {"streams", streams}, {"sizes", sizes}};
}

struct Page {
  nlohmann::json methods = nlohmann::json::object();
  std::string images;  // <img> elements holding the PNG levels
  int next_image = 0;

  nlohmann::json png_levels(const std::vector<Image>& levels) {
    nlohmann::json ids = nlohmann::json::array();
    for (const Image& l : levels) {
      const std::string id = fmt::format("tk-img-{}", next_image++);
      images += fmt::format("<img id=\"{}\" alt=\"\" src=\"data:image/png;base64,{}\">\n", id, base64(encode_png(l)));
      ids.push_back(id);
    }
    return {{"format", "rgba8"}, {"levels", ids}};
  }
  static nlohmann::json half_levels(const std::vector<FloatImage>& levels, bool lut) {
    nlohmann::json data = nlohmann::json::array();
    for (const FloatImage& l : levels)
      data.push_back({{"width", l.width}, {"height", l.height}, {"data", half_base64(l)}});
    return {{"format", "rgba16f"}, {"levels", data}, {"clamp", lut}};
  }

  // `recipes`: the uniform tables (hex, hpn); `tiling`: how the page makes the tiles method's
  // look-up textures. `check`: the tables and the textures' FNV-1a for the page's own seed.
  void add(const RenderSource& src, const RenderOptions& o, nlohmann::json textures, nlohmann::json recipes,
           nlohmann::json tiling = nullptr) {
    nlohmann::json check = nlohmann::json::object();
    for (const auto& [name, values] : glsl_table_uniforms(src, o)) check[name] = values;
    for (const GlslTableTexture& t : glsl_table_textures(src, o))
      check[t.sampler] = std::to_string(
          StableHash().add(std::string_view(reinterpret_cast<const char*>(t.texels.data()), t.texels.size())).fnv());
    methods[render_method_name(src.method)] = {{"shader", glsl_fragment_shader(src, o, GlslMode::Texture)},
                                               {"unit", src.unit_px()},
                                               {"textures", std::move(textures)},
                                               {"tables", std::move(recipes)},
                                               {"tiling", std::move(tiling)},
                                               {"check", std::move(check)},
                                               {"memory_bytes", src.memory_bytes()}};
  }
};

// The page's script: seeded tables, the view's rows, WebGL2, the controls.
constexpr std::string_view kScript = R"JS(
'use strict';
const D = JSON.parse(document.getElementById('tk-data').textContent);
const query = new URLSearchParams(location.search);
const capture = query.get('capture') === '1';
const canvas = document.getElementById('view');
const msg = document.getElementById('msg');
function fail(text) { msg.textContent = text; msg.hidden = false; document.title = 'error: ' + text; throw new Error(text); }

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

// The tiles method's look-up textures for a seed (texture/glsl_sampler.hpp, glsl_table_textures),
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

// The view's rows in fixed point (texture/view.hpp, view_rows), the same double arithmetic.
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

const methods = Object.keys(D.methods);
const number = (name, fallback) => { const v = query.get(name); return v === null ? fallback : Number(v); };
const state = {
  method: query.get('method') || methods[0],
  u: number('u', 0), v: number('v', 0), scale: number('scale', 1), tilt: number('tilt', capture ? 0 : 2),
  seed: BigInt(query.get('seed') || D.seed), aniso: number('aniso', D.aniso),
};
if (!D.methods[state.method]) fail('method ' + state.method + ' is not in this page (' + methods.join(', ') + ')');
if (capture) {
  const size = /^(\d+)x(\d+)$/.exec(query.get('size') || '');
  if (!size) fail('capture=1 needs size=WxH');
  canvas.width = Number(size[1]);
  canvas.height = Number(size[2]);
  document.getElementById('ui').hidden = true;
}

const gl = canvas.getContext('webgl2', {antialias: false, alpha: false, depth: false, stencil: false, preserveDrawingBuffer: true});
const programs = {}, tableCache = {};
let rowTexture = null;

function compile(type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) fail('GLSL: ' + gl.getShaderInfoLog(s));
  return s;
}
function upload(spec) {
  const t = gl.createTexture(), mip = spec.levels.length > 1;
  gl.bindTexture(gl.TEXTURE_2D, t);
  spec.levels.forEach((level, k) => {
    if (spec.format === 'rgba8') {
      gl.texImage2D(gl.TEXTURE_2D, k, gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE, document.getElementById(level));
    } else {
      const bytes = Uint8Array.from(atob(level.data), c => c.charCodeAt(0));
      gl.texImage2D(gl.TEXTURE_2D, k, gl.RGBA16F, level.width, level.height, 0, gl.RGBA, gl.HALF_FLOAT,
                    new Uint16Array(bytes.buffer));
    }
  });
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAX_LEVEL, spec.levels.length - 1);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, mip ? gl.LINEAR_MIPMAP_LINEAR : gl.LINEAR);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
  const wrap = spec.clamp ? gl.CLAMP_TO_EDGE : gl.REPEAT;
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, wrap);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, wrap);
  return t;
}
function program(name) {
  if (programs[name]) return programs[name];
  const m = D.methods[name], p = gl.createProgram();
  gl.attachShader(p, compile(gl.VERTEX_SHADER, D.vertex));
  gl.attachShader(p, compile(gl.FRAGMENT_SHADER, m.shader));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) fail('GLSL link: ' + gl.getProgramInfoLog(p));
  // The port of the seeded tables must give the C++ tables for the page's own seed.
  for (const r of m.tables) {
    const mine = hashTable(r, BigInt(D.seed)), theirs = m.check[r.name];
    if (mine.length !== theirs.length || mine.some((v, i) => v !== theirs[i])) fail('hash table ' + r.name + ' differs from tilekit\'s');
  }
  if (m.tiling) {
    for (const t of tilingTextures(m.tiling, BigInt(D.seed)))
      if (fnv(t.data) !== m.check[t.sampler]) fail('look-up texture ' + t.sampler + ' differs from tilekit\'s');
  }
  gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
  gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
  gl.pixelStorei(gl.UNPACK_PREMULTIPLY_ALPHA_WEBGL, false);
  programs[name] = {p, textures: m.textures.map(spec => ({unit: spec.unit, sampler: spec.sampler, texture: upload(spec)}))};
  return programs[name];
}

function draw() {
  const m = D.methods[state.method], prog = program(state.method), W = canvas.width, H = canvas.height;
  let view;
  try { view = viewRows(W, H, state.scale, state.u, state.v, state.tilt, m.unit); } catch (e) { fail(e.message); }
  gl.useProgram(prog.p);
  for (const t of prog.textures) {
    gl.activeTexture(gl.TEXTURE0 + t.unit);
    gl.bindTexture(gl.TEXTURE_2D, t.texture);
    gl.uniform1i(gl.getUniformLocation(prog.p, t.sampler), t.unit);
  }
  if (!rowTexture) rowTexture = gl.createTexture();
  gl.activeTexture(gl.TEXTURE1);
  gl.bindTexture(gl.TEXTURE_2D, rowTexture);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32I, 2, H, 0, gl.RGBA_INTEGER, gl.INT, view.rows);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  gl.uniform1i(gl.getUniformLocation(prog.p, 'tk_rows'), 1);
  gl.uniform1f(gl.getUniformLocation(prog.p, 'tk_dudy_step'), view.dudyStep);
  gl.uniform1i(gl.getUniformLocation(prog.p, 'tk_height'), H);
  gl.uniform1i(gl.getUniformLocation(prog.p, 'tk_max_aniso'), state.aniso);
  gl.uniform2i(gl.getUniformLocation(prog.p, 'tk_origin'), 0, 0);
  for (const r of m.tables) {
    const key = state.method + ':' + r.name + ':' + state.seed;
    if (!tableCache[key]) tableCache[key] = hashTable(r, state.seed);
    gl.uniform4iv(gl.getUniformLocation(prog.p, r.name), tableCache[key]);
  }
  if (m.tiling) {
    const key = state.method + ':' + state.seed;
    if (!tableCache[key]) tableCache[key] = tilingTextures(m.tiling, state.seed).map(t => {
      const texture = gl.createTexture(), rg = t.channels === 2;
      gl.activeTexture(gl.TEXTURE0 + t.unit);
      gl.bindTexture(gl.TEXTURE_2D, texture);
      gl.texImage2D(gl.TEXTURE_2D, 0, rg ? gl.RG8UI : gl.RGBA8UI, t.width, t.height, 0, rg ? gl.RG_INTEGER : gl.RGBA_INTEGER,
                    gl.UNSIGNED_BYTE, t.data);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      return {unit: t.unit, sampler: t.sampler, texture};
    });
    for (const t of tableCache[key]) {
      gl.activeTexture(gl.TEXTURE0 + t.unit);
      gl.bindTexture(gl.TEXTURE_2D, t.texture);
      gl.uniform1i(gl.getUniformLocation(prog.p, t.sampler), t.unit);
    }
  }
  gl.viewport(0, 0, W, H);
  gl.drawArrays(gl.TRIANGLES, 0, 3);
  if (!capture) info();
}

// The interactive page: drag to pan, wheel to zoom (about the cursor), slider to tilt.
let pending = false;
function redraw() { if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; draw(); }); } }
function info() {
  document.getElementById('info').textContent = state.method + ', origin ' + state.u.toFixed(1) + ',' +
    state.v.toFixed(1) + ', scale ' + state.scale.toFixed(3) + ', tilt ' + state.tilt + ', anisotropy ' + state.aniso +
    'x, seed ' + state.seed + ', ' + (D.methods[state.method].memory_bytes / 1048576).toFixed(1) + ' MiB';
}
function interactive() {
  const resize = () => { canvas.width = innerWidth; canvas.height = innerHeight; redraw(); };
  addEventListener('resize', resize);
  let drag = null;
  canvas.addEventListener('pointerdown', e => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointerup', () => { drag = null; });
  canvas.addEventListener('pointermove', e => {
    if (!drag) return;
    state.u -= (e.clientX - drag[0]) * state.scale;
    state.v -= (e.clientY - drag[1]) * state.scale;
    drag = [e.clientX, e.clientY];
    redraw();
  });
  canvas.addEventListener('wheel', e => {
    e.preventDefault();
    const f = Math.exp(Math.max(-1, Math.min(1, e.deltaY * 0.002)));
    const unit = D.methods[state.method].unit, limit = unit / (1 + state.tilt) * 1.9;  // under 2 tiles per pixel
    const next = Math.min(limit, Math.max(1 / 64, state.scale * f));
    state.u += e.clientX * (state.scale - next);
    state.v += e.clientY * (state.scale - next);
    state.scale = next;
    redraw();
  }, {passive: false});
  const tilt = document.getElementById('tilt'), aniso = document.getElementById('aniso'), seed = document.getElementById('seed');
  tilt.value = state.tilt;
  tilt.addEventListener('input', () => { state.tilt = Number(tilt.value); redraw(); });
  aniso.value = String(state.aniso);
  aniso.addEventListener('change', () => { state.aniso = Number(aniso.value); redraw(); });
  seed.value = String(state.seed);
  seed.addEventListener('change', () => { if (/^\d+$/.test(seed.value)) { state.seed = BigInt(seed.value); redraw(); } });
  const buttons = document.getElementById('methods');
  for (const name of methods) {
    const b = document.createElement('button');
    b.textContent = name;
    b.addEventListener('click', () => {
      state.method = name;
      for (const other of buttons.children) other.className = other === b ? 'on' : '';
      redraw();
    });
    if (name === state.method) b.className = 'on';
    buttons.appendChild(b);
  }
  resize();
}

addEventListener('load', () => {
  if (!gl) fail('this browser gives no WebGL2 context');
  if (capture) {
    draw();
    document.title = 'drawn';
  } else {
    interactive();
  }
});
)JS";

}  // namespace

std::string preview_html(const TextureAtlas& atlas, const ExemplarSurface* exemplar, const RenderOptions& o) {
  Page page;
  const RenderSource tiles{RenderMethod::Tiles, &atlas, nullptr};
  {
    const DirectTiling tiling(atlas.lookup.kind, atlas.lookup.colours, o.hash, o.seed);
    const auto hashes = tiling.hashes();
    nlohmann::json recipes = nlohmann::json::array();
    if (hashes.size() == 1) {
      recipes.push_back(recipe("tk_lattice0_P", *hashes[0], {}));
    } else {
      recipes.push_back(recipe("tk_lattice0_P", *hashes[0], {1}));
      recipes.push_back(recipe("tk_lattice1_P", *hashes[1], {2}));
    }
    nlohmann::json spec = {{"kind", kind_name(atlas.lookup.kind)}, {"colors", atlas.lookup.colours},
                           {"tables", recipes}};
    if (glsl_tile_cell_texture(atlas.lookup, o.hash)) spec["positions"] = atlas.lookup.positions;
    nlohmann::json t = page.png_levels(atlas.levels);
    t["unit"] = 0;
    t["sampler"] = "tk_atlas";
    page.add(tiles, o, nlohmann::json::array({t}), nlohmann::json::array(), spec);
  }
  if (exemplar) {
    const PatchHashes h(o.hash, o.seed);
    const nlohmann::json recipes = {recipe("tk_patch_x_P", h.x, {1}), recipe("tk_patch_y_P", h.y, {2})};
    nlohmann::json levels = page.png_levels(exemplar->levels);
    levels.update({{"unit", 0}, {"sampler", "tk_exemplar"}});
    page.add(RenderSource{RenderMethod::Hex, nullptr, exemplar}, o, nlohmann::json::array({levels}), recipes);
    nlohmann::json gaussian = Page::half_levels(exemplar->gaussian, false),
                   lut = Page::half_levels({exemplar->lut}, true);
    gaussian.update({{"unit", 0}, {"sampler", "tk_exemplar"}});
    lut.update({{"unit", 2}, {"sampler", "tk_lut"}});
    page.add(RenderSource{RenderMethod::Hpn, nullptr, exemplar}, o, nlohmann::json::array({gaussian, lut}), recipes);
  }
  const nlohmann::json data = {{"methods", page.methods},
                               {"vertex", glsl_vertex_shader()},
                               {"seed", std::to_string(o.seed)},
                               {"aniso", o.max_aniso}};
  std::string json = data.dump();
  // Inside <script>, "</" could end the element early; "<\/" is the same JSON string.
  for (std::size_t p = json.find("</"); p != std::string::npos; p = json.find("</", p + 3)) json.replace(p, 2, "<\\/");
  const std::string title =
      fmt::format("tilekit preview: {} tiles over {} colours, {} px{}", kind_name(atlas.lookup.kind),
                  atlas.lookup.colours, atlas.tile_px, exemplar ? ", exemplar " + exemplar->name : "");
  std::string html = "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>";
  html += title;
  html +=
      "</title>\n<style>\n"
      "html, body { margin: 0; height: 100%; overflow: hidden; background: #222; color: #eee; font: 13px sans-serif; "
      "}\n"
      "canvas { display: block; }\n"
      "#ui { position: fixed; left: 8px; top: 8px; padding: 8px; background: rgba(0, 0, 0, 0.7); border-radius: 4px; "
      "}\n"
      "#ui button.on { background: #6a6; }\n"
      "#msg { position: fixed; left: 8px; bottom: 8px; color: #f88; white-space: pre-wrap; }\n"
      "</style></head><body>\n<canvas id=\"view\"></canvas>\n<div id=\"ui\"><b>";
  html += title;
  html +=
      "</b><br><span id=\"info\"></span><br>\n"
      "method <span id=\"methods\"></span> tilt <input id=\"tilt\" type=\"range\" min=\"0\" max=\"12\" step=\"0.1\">\n"
      "anisotropy <select id=\"aniso\"><option>1</option><option>2</option><option>4</option><option>8</option>"
      "<option>16</option></select> seed <input id=\"seed\" size=\"8\"><br>drag: pan, wheel: zoom</div>\n"
      "<pre id=\"msg\" hidden></pre>\n<div hidden>\n";
  html += page.images;
  html += "</div>\n<script type=\"application/json\" id=\"tk-data\">";
  html += json;
  html += "</script>\n<script>";
  html += kScript;
  html += "</script>\n</body></html>\n";
  return html;
}

}  // namespace tilekit
