// atlas.ktx2 in the users' tools: npm's ktx-parse reads every level with the right format, colour
// space and key/value data, and three.js's KTX2Loader loads it in headless chromium (no Basis
// transcoder: uncompressed RGBA8 needs none), where atlas.glsl samples it and the picture equals
// `tilekit texture render` (the CPU reference) within 2/255:
//  - the data atlas (--color-space linear, RGBA8 UNORM): a tilted view with 16x anisotropic taps
//    and flat views at scales 1, 2, 4 and 8 (mip levels 0-3);
//  - the colour atlas (RGBA8 sRGB, decoded to linear light by the GPU, encoded back by the shader):
//    the flat views, whose pixels each read one texel of one level (the CPU filters sRGB bytes as
//    they are, the GPU in linear light, so blended texels would differ by design);
//  - a float map's atlas (R32G32B32A32_SFLOAT): ktx-parse only.
// Usage: NODE_PATH=$(scripts/npm-deps.sh)/node_modules node --experimental-websocket THIS TILEKIT SOURCE_DIR
// Exit 0 on success; skipped (exit 77, "skipped" printed) where chromium or the npm packages are
// missing, unless TILEKIT_REQUIRE_BROWSER=1.
import { execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const [tilekit, source] = process.argv.slice(2);
const modules = process.env.NODE_PATH || '';
const skip = why => {
  if (process.env.TILEKIT_REQUIRE_BROWSER === '1') { console.error('FAIL: ' + why); process.exit(1); }
  console.log('skipped: ' + why);
  process.exit(77);
};
try { execFileSync('sh', ['-c', 'command -v chromium'], { stdio: 'ignore' }); } catch { skip('chromium is not installed'); }
if (!fs.existsSync(path.join(modules, 'ktx-parse')) || !fs.existsSync(path.join(modules, 'three')))
  skip('NODE_PATH has no ktx-parse and three (scripts/npm-deps.sh installs them)');
const { read, write } = await import(path.join(modules, 'ktx-parse/dist/index.mjs'));
const { evaluatePage } = await import(path.join(source, 'tests/scripts/chromium_eval.mjs'));
const { viewRows } = createRequire(import.meta.url)(path.join(source, 'render/preview_tables.js'));

let failures = 0;
const check = (ok, what) => { if (!ok) { console.error('FAIL: ' + what); ++failures; } };
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tk-ktx2-'));
const { tileSet, pageCompare } = await import(path.join(source, 'tests/scripts/tile_fixture.mjs'));
const run = tileSet(tilekit, dir);


const views = [
  { name: 'tilted', size: [96, 64], origin: [37.5, -20], scale: 0.7, tilt: 2.5, aniso: 16, linearOnly: true },
  // the hardware filter: one textureGrad, the texture's anisotropy 16 (SwiftShader's rule on the CPU)
  { name: 'tilted-hardware', size: [96, 64], origin: [37.5, -20], scale: 0.7, tilt: 2.5, aniso: 16, linearOnly: true, filter: 'hardware' },
  ...[1, 2, 4, 8].map(s => ({ name: `flat-x${s}`, size: [64, 48], origin: [3 * s, 5 * s], scale: s, tilt: 0, aniso: 16 })),
];
const cases = [];
for (const space of ['linear', 'srgb']) {
  const atlas = path.join(dir, space, 'atlas.png');
  fs.mkdirSync(path.dirname(atlas));
  run(['texture', 'atlas', path.join(dir, 't'), '--out', atlas, '--color-space', space]);
  const manifest = JSON.parse(fs.readFileSync(path.join(dir, space, 'atlas.json'), 'utf8'));
  const bytes = new Uint8Array(fs.readFileSync(path.join(dir, space, 'atlas.ktx2')));
  // ktx-parse: the container, every level, the format and colour space, the key/value data.
  const c = read(bytes);
  const dfd = c.dataFormatDescriptor[0];
  check(c.vkFormat === (space === 'srgb' ? 43 : 37), `${space}: vkFormat ${c.vkFormat}`);
  check(c.typeSize === 1 && c.pixelDepth === 0 && c.layerCount === 0 && c.faceCount === 1 && c.supercompressionScheme === 0, `${space}: header`);
  check(c.pixelWidth === manifest.levels[0].width && c.pixelHeight === manifest.levels[0].height, `${space}: size`);
  check(c.levels.length === manifest.levels.length && c.levelCount === manifest.levels.length, `${space}: ${c.levels.length} levels, manifest ${manifest.levels.length}`);
  c.levels.forEach((l, k) => check(l.levelData.byteLength === manifest.levels[k].width * manifest.levels[k].height * 4 && l.uncompressedByteLength === l.levelData.byteLength, `${space}: level ${k} length`));
  check(dfd.colorModel === 1 && dfd.colorPrimaries === 1 && dfd.transferFunction === (space === 'srgb' ? 2 : 1), `${space}: DFD model/primaries/transfer ${dfd.colorModel}/${dfd.colorPrimaries}/${dfd.transferFunction}`);
  check(dfd.samples.length === 4 && dfd.bytesPlane[0] === 4 && dfd.samples.every((s, i) => s.bitOffset === 8 * i && s.bitLength === 7 && s.sampleUpper === 255), `${space}: DFD samples`);
  check((dfd.samples[3].channelType & 15) === 15 && (dfd.samples[3].channelType & 0x10) === (space === 'srgb' ? 0x10 : 0), `${space}: alpha sample`);
  const text = v => (typeof v === 'string' ? v : new TextDecoder().decode(v)).replace(/\0$/, '');
  check(text(c.keyValue.KTXorientation) === 'rd', `${space}: KTXorientation`);
  const info = JSON.parse(text(c.keyValue['tilekit.atlas']));
  check(info.rows === manifest.rows && info.cols === manifest.cols && info.tile_px === manifest.tile_px && info.kind === manifest.kind, `${space}: tilekit.atlas ${JSON.stringify(info)}`);
  // ktx-parse's own writer makes the same bytes from what it read: nothing it does not understand.
  const again = write(c, { keepWriter: true });
  check(again.length === bytes.length && again.every((b, i) => b === bytes[i]), `${space}: ktx-parse's write(read(file)) differs from the file`);
  for (const v of views) {
    if (v.linearOnly && space === 'srgb') continue;
    const ref = path.join(dir, space, v.name + '.png');
    run(['texture', 'render', '--atlas', atlas, '--size', v.size.join('x'), '--origin', v.origin.join(','), '--scale', String(v.scale), '--tilt', String(v.tilt), '--aniso', String(v.aniso), '--filter', v.filter || 'taps', '--quiet', '--out', ref]);
    const r = viewRows(v.size[0], v.size[1], v.scale, v.origin[0], v.origin[1], v.tilt, manifest.tile_px);
    cases.push({ name: `${space}/${v.name}`, space, ktx2: `${space}/atlas.ktx2`, ref: `${space}/${v.name}.png`, w: v.size[0], h: v.size[1], aniso: v.aniso, hw: v.filter === 'hardware', rows: Array.from(r.rows), dudyStep: r.dudyStep });
  }
  fs.copyFileSync(path.join(dir, space, 'atlas.glsl'), path.join(dir, space + '.glsl'));
}

// A float map (a 32-bit float TIFF of heights -3.5 .. 1200.25, written here by hand: one strip,
// uncompressed) atlased beside the tiles: its atlas-h.ktx2 is R32G32B32A32_SFLOAT, and ktx-parse
// reads the format, the float descriptor and every level, and writes the same bytes back.
{
  const w = 96, h = 96, tags = [[256, 3, w], [257, 3, h], [258, 3, 32], [259, 3, 1], [262, 3, 1], [273, 4, 8 + 2 + 12 * 10 + 4],
    [277, 3, 1], [278, 3, h], [279, 4, w * h * 4], [339, 3, 3]];
  const tif = new DataView(new ArrayBuffer(8 + 2 + 12 * tags.length + 4 + w * h * 4));
  tif.setUint32(0, 0x002A4949, true); tif.setUint32(4, 8, true); tif.setUint16(8, tags.length, true);
  tags.forEach(([tag, type, v], i) => {
    const at = 10 + 12 * i;
    tif.setUint16(at, tag, true); tif.setUint16(at + 2, type, true); tif.setUint32(at + 4, 1, true);
    if (type === 3) tif.setUint16(at + 8, v, true); else tif.setUint32(at + 8, v, true);
  });
  for (let i = 0; i < w * h; ++i) tif.setFloat32(8 + 2 + 12 * tags.length + 4 + 4 * i, -3.5 + ((i * 37) % 128) * (1203.75 / 127), true);
  fs.writeFileSync(path.join(dir, 'h.tif'), new Uint8Array(tif.buffer));
  run(['texture', 'tiles', '--exemplar', path.join(dir, 'ex.png'), '--map', 'h=' + path.join(dir, 'h.tif'), '--colors', '2', '--tile-px', '16', '--search', '2', '--out', path.join(dir, 'fm'), '--quiet']);
  run(['texture', 'atlas', path.join(dir, 'fm'), '--out', path.join(dir, 'float', 'atlas.png'), '--quiet']);
  const manifest = JSON.parse(fs.readFileSync(path.join(dir, 'float', 'atlas-h.json'), 'utf8'));
  const bytes = new Uint8Array(fs.readFileSync(path.join(dir, 'float', 'atlas-h.ktx2')));
  const c = read(bytes), dfd = c.dataFormatDescriptor[0];
  check(manifest.bits === 32 && manifest.format === 'exr float' && manifest.levels[0].file === 'atlas-h.exr', `float: manifest ${manifest.bits} ${manifest.format}`);
  check(c.vkFormat === 109 && c.typeSize === 4, `float: vkFormat ${c.vkFormat}, typeSize ${c.typeSize}`);
  check(dfd.colorModel === 1 && dfd.transferFunction === 1 && dfd.bytesPlane[0] === 16, 'float: DFD model/transfer/bytes');
  check(dfd.samples.length === 4 && dfd.samples.every((s, i) => s.bitOffset === 32 * i && s.bitLength === 31 && (s.channelType & 0xC0) === 0xC0 && s.sampleLower >>> 0 === 0xBF800000 && s.sampleUpper >>> 0 === 0x3F800000), 'float: DFD samples (float, signed, -1 .. 1)');
  check(c.levels.length === manifest.levels.length, `float: ${c.levels.length} levels, manifest ${manifest.levels.length}`);
  c.levels.forEach((l, k) => check(l.levelData.byteLength === manifest.levels[k].width * manifest.levels[k].height * 16, `float: level ${k} length`));
  const l0 = new Float32Array(c.levels[0].levelData.slice().buffer);
  let lo = Infinity, hi = -Infinity;
  for (let i = 0; i < l0.length; i += 4) lo = Math.min(lo, l0[i]), hi = Math.max(hi, l0[i]);
  check(lo >= -3.5 && lo < 0 && hi > 1000 && hi <= 1200.25, `float: level 0 heights ${lo} .. ${hi}`);
  const again = write(c, { keepWriter: true });
  check(again.length === bytes.length && again.every((b, i) => b === bytes[i]), "float: ktx-parse's write(read(file)) differs from the file");
}

// The page: three.js from the npm package, KTX2Loader, atlas.glsl plus the renderer's main().
const three = 'file://' + path.join(modules, 'three/build/three.module.js');
const loader = 'file://' + path.join(modules, 'three/examples/jsm/loaders/KTX2Loader.js');
const glsl = Object.fromEntries(['linear', 'srgb'].map(s => [s, fs.readFileSync(path.join(dir, s + '.glsl'), 'utf8')]));
const files = Object.fromEntries(cases.flatMap(k => [k.ktx2, k.ref]).map(f => [f, fs.readFileSync(path.join(dir, f)).toString('base64')]));
const main = `
uniform highp isampler2D tk_rows;
uniform float tk_dudy_step;
uniform int tk_height, tk_max_aniso, tk_srgb, tk_hw;
out vec4 tk_colour;
void main() {  // render/glsl_sampler.cpp, GlslMode::Texture
  ivec2 px = ivec2(gl_FragCoord.xy);
  int j = tk_height - 1 - px.y;
  ivec4 r0 = texelFetch(tk_rows, ivec2(0, j), 0), r1 = texelFetch(tk_rows, ivec2(1, j), 0);
  uint fu = uint(r0.y) + uint(px.x) * uint(r0.z);
  ivec2 tile = ivec2(r0.x + int(fu >> 16u), r0.w);
  ivec2 frac = ivec2(int(fu & 65535u), r1.x);
  float dudy = intBitsToFloat(r1.w) + float(px.x) * tk_dudy_step;
  int taps; float lod; ivec2 axis;
  vec2 dx = vec2(intBitsToFloat(r1.y), 0.0), dy = vec2(dudy, intBitsToFloat(r1.z));
  tk_footprint(dx, dy, tk_max_aniso, taps, lod, axis);
  vec4 c = tk_hw == 1 ? tk_sample_grad(tile, vec2(frac) / 65536.0, dx, dy) : tk_sample(tile, frac, taps, lod, axis);
  if (tk_srgb == 1) {  // the GPU decoded the sRGB atlas to linear light: encode it back (sRGB OETF)
    vec3 l = clamp(c.rgb, 0.0, 1.0);
    c.rgb = mix(l * 12.92, 1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, l));
  }
  tk_colour = c;
}`;
const html = `<!doctype html><html><body>
<script type="importmap">${JSON.stringify({ imports: { three } })}</script>
<script type="module">
import * as THREE from 'three';
import { KTX2Loader } from '${loader}';
const cases = ${JSON.stringify(cases)}, files = ${JSON.stringify(files)}, glsl = ${JSON.stringify(glsl)};
const main = ${JSON.stringify(main)};
const bytes = f => Uint8Array.from(atob(files[f]), c => c.charCodeAt(0));
${pageCompare}
async function run() {
  const canvas = document.createElement('canvas');
  const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true, antialias: false });
  renderer.setPixelRatio(1);
  const loader = new KTX2Loader().detectSupport(renderer);  // no transcoder path: never fetched
  const out = [];
  for (const k of cases) {
    const tex = await new Promise((res, rej) => loader.parse(bytes(k.ktx2).buffer, res, rej));
    tex.wrapS = tex.wrapT = THREE.RepeatWrapping;
    tex.minFilter = THREE.LinearMipmapLinearFilter;
    tex.magFilter = THREE.LinearFilter;
    tex.anisotropy = k.hw ? 16 : 1;
    tex.needsUpdate = true;
    const rows = new THREE.DataTexture(new Int32Array(k.rows), 2, k.h, THREE.RGBAIntegerFormat, THREE.IntType);
    rows.internalFormat = 'RGBA32I';
    rows.needsUpdate = true;
    renderer.setSize(k.w, k.h, false);
    const material = new THREE.RawShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader: 'in vec3 position; void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }',
      fragmentShader: 'precision highp float;\\nprecision highp int;\\nprecision highp isampler2D;\\n' + glsl[k.space] + main,
      uniforms: { tk_atlas: { value: tex }, tk_rows: { value: rows }, tk_dudy_step: { value: k.dudyStep },
                  tk_height: { value: k.h }, tk_max_aniso: { value: k.aniso }, tk_srgb: { value: k.space === 'srgb' ? 1 : 0 },
                  tk_hw: { value: k.hw ? 1 : 0 } },
    });
    const scene = new THREE.Scene();
    scene.add(new THREE.Mesh(new THREE.PlaneGeometry(2, 2), material));
    renderer.render(scene, new THREE.Camera());
    const gl = renderer.getContext(), px = new Uint8Array(k.w * k.h * 4);
    gl.readPixels(0, 0, k.w, k.h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const top = new Uint8Array(px.length);  // readPixels' rows from the bottom
    for (let y = 0; y < k.h; ++y) top.set(px.subarray((k.h - 1 - y) * k.w * 4, (k.h - y) * k.w * 4), y * k.w * 4);
    const worst = await largestDifference(top, bytes(k.ref), k.w, k.h);
    out.push({ name: k.name, worst, colorSpace: tex.colorSpace, levels: tex.mipmaps.length,
               maxAnisotropy: renderer.capabilities.getMaxAnisotropy() });
  }
  return out;
}
window.tkResult = run().catch(e => ({ error: String(e && e.stack || e) }));
</script></body></html>`;
fs.writeFileSync(path.join(dir, 'page.html'), html);
const result = await evaluatePage(path.join(dir, 'page.html'), { seconds: 300 });
if (result.error) { console.error('FAIL: the page: ' + result.error); process.exit(1); }
for (const r of result) {
  console.log(`${r.name}: largest difference ${r.worst}/255 (${r.levels} levels, ${r.colorSpace}; anisotropy up to ${r.maxAnisotropy})`);
  check(r.worst <= 2, `${r.name}: ${r.worst}/255 from the CPU reference`);
  check(r.colorSpace === (r.name.startsWith('srgb') ? 'srgb' : 'srgb-linear'), `${r.name}: three's colour space ${r.colorSpace}`);
}
check(result.length === cases.length, 'every case rendered');

// examples/three-atlas served over http (python3 -m http.server), as its README says: it loads the
// sRGB atlas and draws a textured ground plane (many colours, nothing left black below the horizon).
const site = path.join(dir, 'site');
fs.mkdirSync(site);
for (const f of ['index.html', 'main.js']) fs.copyFileSync(path.join(source, 'examples/three-atlas', f), path.join(site, f));
for (const f of ['atlas.ktx2', 'atlas.glsl']) fs.copyFileSync(path.join(dir, 'srgb', f), path.join(site, f));
fs.symlinkSync(modules, path.join(site, 'node_modules'));
const { spawn } = await import('node:child_process');
const server = spawn('python3', ['-m', 'http.server', '0', '--bind', '127.0.0.1', '--directory', site], { stdio: ['ignore', 'pipe', 'pipe'] });
try {
  const port = await new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', d => { text += d; const m = /port (\d+)/.exec(text); if (m) resolve(m[1]); });
    server.on('exit', () => reject(new Error('http.server exited')));
    setTimeout(() => reject(new Error('http.server did not start')), 20000);
  });
  const drawn = await evaluatePage(`http://127.0.0.1:${port}/index.html`, { seconds: 120, expression: `!window.tkReady ? undefined :
    new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => {
      const c = document.querySelector('canvas'), w = 200, h = 150, x = new OffscreenCanvas(w, h).getContext('2d');
      x.drawImage(c, 0, 0, w, h);
      const d = x.getImageData(0, h / 2, w, h / 2).data, colours = new Set();
      let black = 0;
      for (let i = 0; i < d.length; i += 4) { colours.add(d[i] << 16 | d[i + 1] << 8 | d[i + 2]); if (d[i] + d[i + 1] + d[i + 2] === 0) ++black; }
      r({ colours: colours.size, black, pixels: d.length / 4 });
    })))` });
  console.log(`examples/three-atlas: ${drawn.colours} colours, ${drawn.black} of ${drawn.pixels} pixels black below the horizon`);
  check(drawn.colours > 100 && drawn.black === 0, 'examples/three-atlas did not draw the atlas');
} finally {
  server.kill();
}
if (failures) process.exit(1);
fs.rmSync(dir, { recursive: true, force: true });
console.log('ok');
