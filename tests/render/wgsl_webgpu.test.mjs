// atlas.wgsl in headless chromium's WebGPU (SwiftShader's Vulkan): the module compiles with no
// message at all (getCompilationInfo), and a view drawn with it, the atlas loaded from atlas.ktx2
// (every level, read by npm's ktx-parse in the page), equals `tilekit texture render` within 2/255:
// both hashes, a tilted view with 16 anisotropic taps and flat views at mip levels 0-3 (data
// atlases, RGBA8 UNORM, so that the GPU filters the bytes the CPU does).
// Usage: NODE_PATH=$(scripts/npm-deps.sh)/node_modules node --experimental-websocket THIS TILEKIT SOURCE_DIR
// (tests/scripts/node-browser-test.sh). Skipped (exit 77) where chromium, the npm packages or a
// WebGPU adapter are missing, unless TILEKIT_REQUIRE_BROWSER=1.
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
if (!fs.existsSync(path.join(modules, 'ktx-parse'))) skip('NODE_PATH has no ktx-parse (scripts/npm-deps.sh installs it)');
const { evaluatePage } = await import(path.join(source, 'tests/scripts/chromium_eval.mjs'));
const { tileSet, pageCompare } = await import(path.join(source, 'tests/scripts/tile_fixture.mjs'));
const { viewRows } = createRequire(import.meta.url)(path.join(source, 'render/preview_tables.js'));

let failures = 0;
const check = (ok, what) => { if (!ok) { console.error('FAIL: ' + what); ++failures; } };
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'tk-wgsl-'));
const run = tileSet(tilekit, dir);

const views = [
  { name: 'tilted', size: [96, 64], origin: [37.5, -20], scale: 0.7, tilt: 2.5 },
  ...[1, 2, 4, 8].map(s => ({ name: `flat-x${s}`, size: [64, 48], origin: [3 * s, 5 * s], scale: s, tilt: 0 })),
];
const cases = [], wgsl = {}, files = {};
const filters = ['taps', 'hardware'];  // hardware: textureSampleGrad, maxAnisotropy 16
for (const hash of ['perm', 'long-period']) {
  const atlas = path.join(dir, hash, 'atlas.png');
  fs.mkdirSync(path.dirname(atlas));
  run(['texture', 'atlas', path.join(dir, 't'), '--out', atlas, '--color-space', 'linear', '--hash', hash, '--seed', '7']);
  wgsl[hash] = fs.readFileSync(path.join(dir, hash, 'atlas.wgsl'), 'utf8');
  files[hash + '/atlas.ktx2'] = fs.readFileSync(path.join(dir, hash, 'atlas.ktx2')).toString('base64');
  const tilePx = JSON.parse(fs.readFileSync(path.join(dir, hash, 'atlas.json'), 'utf8')).tile_px;
  for (const filter of filters) for (const v of views) {
    const name = `${hash}/${v.name}${filter === 'taps' ? '' : '-' + filter}`;
    const ref = path.join(dir, name + '.png');
    run(['texture', 'render', '--atlas', atlas, '--hash', hash, '--seed', '7', '--size', v.size.join('x'), '--origin', v.origin.join(','),
      '--scale', String(v.scale), '--tilt', String(v.tilt), '--aniso', '16', '--filter', filter, '--quiet', '--out', ref]);
    files[name + '.png'] = fs.readFileSync(ref).toString('base64');
    const r = viewRows(v.size[0], v.size[1], v.scale, v.origin[0], v.origin[1], v.tilt, tilePx);
    cases.push({ name, hash, hw: filter === 'hardware', w: v.size[0], h: v.size[1], rows: Array.from(r.rows), dudyStep: r.dudyStep });
  }
}

// The renderer's main() (render/glsl_sampler.cpp, GlslMode::Texture) in WGSL; WebGPU's y runs down.
const main = `
@group(0) @binding(2) var tk_rows: texture_2d<i32>;
struct TkView { dudy_step: f32, max_aniso: i32, hardware: i32, pad1: i32 }
@group(0) @binding(3) var<uniform> tk_view: TkView;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
  return vec4<f32>(f32((i & 1u) << 2u) - 1.0, f32((i & 2u) << 1u) - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
  let px = vec2<i32>(position.xy);
  let r0 = textureLoad(tk_rows, vec2<i32>(0, px.y), 0);
  let r1 = textureLoad(tk_rows, vec2<i32>(1, px.y), 0);
  let fu = u32(r0.y) + u32(px.x) * u32(r0.z);
  let tile = vec2<i32>(r0.x + i32(fu >> 16u), r0.w);
  let sub = vec2<i32>(i32(fu & 65535u), r1.x);
  let dudy = bitcast<f32>(r1.w) + f32(px.x) * tk_view.dudy_step;
  let dx = vec2<f32>(bitcast<f32>(r1.y), 0.0);
  let dy = vec2<f32>(dudy, bitcast<f32>(r1.z));
  if (tk_view.hardware == 1) { return tk_sample_grad(tile, vec2<f32>(sub) / 65536.0, dx, dy); }
  return tk_sample(tile, sub, tk_footprint(dx, dy, tk_view.max_aniso));
}`;
const ktxParse = 'file://' + path.join(modules, 'ktx-parse/dist/index.mjs');
const html = `<!doctype html><html><body><script type="module">
import { read } from '${ktxParse}';
const cases = ${JSON.stringify(cases)}, files = ${JSON.stringify(files)}, wgsl = ${JSON.stringify(wgsl)};
const main = ${JSON.stringify(main)};
const bytes = f => Uint8Array.from(atob(files[f]), c => c.charCodeAt(0));
${pageCompare}
async function run() {
  if (!navigator.gpu) return { skip: 'no navigator.gpu' };
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) return { skip: 'no WebGPU adapter' };
  const device = await adapter.requestDevice();
  const out = [], compilation = {};
  for (const k of cases) {
    const c = read(bytes(k.hash + '/atlas.ktx2'));
    const atlas = device.createTexture({ size: [c.pixelWidth, c.pixelHeight], mipLevelCount: c.levels.length, format: 'rgba8unorm',
                                         usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
    c.levels.forEach((l, i) => {
      const w = Math.max(1, c.pixelWidth >> i), h = Math.max(1, c.pixelHeight >> i);
      device.queue.writeTexture({ texture: atlas, mipLevel: i }, l.levelData, { bytesPerRow: 4 * w, rowsPerImage: h }, [w, h]);
    });
    const rows = device.createTexture({ size: [2, k.h], format: 'rgba32sint', usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
    device.queue.writeTexture({ texture: rows }, new Int32Array(k.rows), { bytesPerRow: 32, rowsPerImage: k.h }, [2, k.h]);
    const view = device.createBuffer({ size: 16, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
    const v = new ArrayBuffer(16);
    new Float32Array(v, 0, 1)[0] = k.dudyStep;
    new Int32Array(v, 4, 2).set([16, k.hw ? 1 : 0]);
    device.queue.writeBuffer(view, 0, v);
    const module = device.createShaderModule({ code: wgsl[k.hash] + main });
    const info = await module.getCompilationInfo();
    compilation[k.hash] = info.messages.map(m => m.type + ' ' + m.lineNum + ':' + m.linePos + ' ' + m.message);
    const pipeline = device.createRenderPipeline({ layout: 'auto', vertex: { module, entryPoint: 'vs' },
      fragment: { module, entryPoint: 'fs', targets: [{ format: 'rgba8unorm' }] } });
    const sampler = device.createSampler({ magFilter: 'linear', minFilter: 'linear', mipmapFilter: 'linear', addressModeU: 'repeat', addressModeV: 'repeat', maxAnisotropy: k.hw ? 16 : 1 });
    const group = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries: [
      { binding: 0, resource: atlas.createView() }, { binding: 1, resource: sampler },
      { binding: 2, resource: rows.createView() }, { binding: 3, resource: { buffer: view } }] });
    const target = device.createTexture({ size: [k.w, k.h], format: 'rgba8unorm', usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
    const stride = Math.ceil(k.w * 4 / 256) * 256;
    const readback = device.createBuffer({ size: stride * k.h, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginRenderPass({ colorAttachments: [{ view: target.createView(), loadOp: 'clear', storeOp: 'store', clearValue: [0, 0, 0, 0] }] });
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, group);
    pass.draw(3);
    pass.end();
    encoder.copyTextureToBuffer({ texture: target }, { buffer: readback, bytesPerRow: stride }, [k.w, k.h]);
    device.queue.submit([encoder.finish()]);
    await readback.mapAsync(GPUMapMode.READ);
    const mapped = new Uint8Array(readback.getMappedRange()), px = new Uint8Array(k.w * k.h * 4);
    for (let y = 0; y < k.h; ++y) px.set(mapped.subarray(y * stride, y * stride + k.w * 4), y * k.w * 4);
    readback.unmap();
    out.push({ name: k.name, worst: await largestDifference(px, bytes(k.name + '.png'), k.w, k.h), levels: c.levels.length });
  }
  return { out, compilation, adapter: adapter.info ? adapter.info.vendor + ' ' + adapter.info.architecture + ' ' + adapter.info.description : '' };
}
window.tkResult = run().catch(e => ({ error: String(e && e.stack || e) }));
</script></body></html>`;
fs.writeFileSync(path.join(dir, 'page.html'), html);
const result = await evaluatePage(path.join(dir, 'page.html'), { webgpu: true, seconds: 300 });
if (result.skip) skip(result.skip);
if (result.error) { console.error('FAIL: the page: ' + result.error); process.exit(1); }
console.log(`WebGPU adapter: ${result.adapter}`);
for (const [hash, messages] of Object.entries(result.compilation)) {
  console.log(`${hash}: atlas.wgsl compiled with ${messages.length} messages`);
  check(messages.length === 0, `${hash}: compilation messages:\n${messages.join('\n')}`);
}
for (const r of result.out) {
  console.log(`${r.name}: largest difference ${r.worst}/255 (${r.levels} levels)`);
  check(r.worst <= 2, `${r.name}: ${r.worst}/255 from the CPU reference`);
}
check(result.out.length === cases.length, 'every case rendered');
if (failures) process.exit(1);
fs.rmSync(dir, { recursive: true, force: true });
console.log('ok');
