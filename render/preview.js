// `texture preview`'s page (render/preview.cpp embeds it after render/preview_tables.js, whose
// functions it calls): the page's data, the view's row table, WebGL2 with the renderer's own
// fragment shaders, and the controls (drag to pan, wheel to zoom, tilt, anisotropy, seed, method).
'use strict';
const D = JSON.parse(document.getElementById('tk-data').textContent);
const query = new URLSearchParams(location.search);
const capture = query.get('capture') === '1';
const canvas = document.getElementById('view');
const msg = document.getElementById('msg');
function fail(text) { msg.textContent = text; msg.hidden = false; document.title = 'error: ' + text; throw new Error(text); }

// Tilekit's method first: the page opens on tiles (the JSON's keys come sorted: hex, hpn, tiles).
const methods = ['tiles', 'hex', 'hpn'].filter(m => D.methods[m]).concat(Object.keys(D.methods).filter(m => !['tiles', 'hex', 'hpn'].includes(m)));
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
      gl.texImage2D(gl.TEXTURE_2D, k, spec.srgb ? gl.SRGB8_ALPHA8 : gl.RGBA8, gl.RGBA, gl.UNSIGNED_BYTE,
                    document.getElementById(level));
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
