// `tilekit fill` on the WFC reference samples, checked by the npm port of the reference
// (wavefunctioncollapse, a peer that shares no code with Tilekit):
//   - every pair of neighbouring cells (wrapping on a torus) is allowed by the port's own
//     propagator, built by the port from the same XML (read here, not by Tilekit);
//   - the picture Tilekit writes equals, pixel for pixel, the port's graphics() of the same map
//     (the tile images rotated and reflected as the reference does, at their own size, no borders);
//   - the fixed cells of a cells file are where the file puts them.
// Usage: node wfc_reference.test.js REPO TILEKIT TMPDIR [SEEDS]   (NODE_PATH: the npm cache's node_modules)
'use strict';
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');
const { execFileSync } = require('child_process');
const wfc = require('wavefunctioncollapse');

const [repo, tilekit, tmp, seedsArg] = process.argv.slice(2);
const seeds = Number(seedsArg || 3);
const dataDir = path.join(repo, 'tilemap', 'data', 'wfc');
fs.mkdirSync(tmp, { recursive: true });

// A PNG decoder for 8-bit grey, RGB, grey+alpha and RGBA, non-interlaced (what the samples and
// Tilekit's encoder use). Returns {width, height, rgba}.
function readPng(file) {
  const buf = fs.readFileSync(file);
  let pos = 8, width = 0, height = 0, type = 0, depth = 0, interlace = 0;
  const idat = [];
  while (pos < buf.length) {
    const len = buf.readUInt32BE(pos);
    const kind = buf.toString('ascii', pos + 4, pos + 8);
    const body = buf.subarray(pos + 8, pos + 8 + len);
    if (kind === 'IHDR') {
      width = body.readUInt32BE(0); height = body.readUInt32BE(4);
      depth = body[8]; type = body[9]; interlace = body[12];
    } else if (kind === 'IDAT') idat.push(body);
    pos += 12 + len;
  }
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[type];
  if (depth !== 8 || !channels || interlace) throw new Error(`${file}: unsupported PNG (type ${type}, depth ${depth})`);
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const px = Buffer.alloc(stride * height);
  for (let y = 0; y < height; y++) {
    const f = raw[y * (stride + 1)];
    for (let x = 0; x < stride; x++) {
      const v = raw[y * (stride + 1) + 1 + x];
      const a = x >= channels ? px[y * stride + x - channels] : 0;
      const b = y > 0 ? px[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? px[(y - 1) * stride + x - channels] : 0;
      let p;
      if (f === 0) p = 0;
      else if (f === 1) p = a;
      else if (f === 2) p = b;
      else if (f === 3) p = (a + b) >> 1;
      else {
        const q = a + b - c, pa = Math.abs(q - a), pb = Math.abs(q - b), pc = Math.abs(q - c);
        p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      px[y * stride + x] = (v + p) & 255;
    }
  }
  const rgba = new Uint8Array(width * height * 4);
  for (let i = 0; i < width * height; i++) {
    const s = px.subarray(i * channels, i * channels + channels);
    const g = channels <= 2;
    rgba[i * 4] = s[0]; rgba[i * 4 + 1] = g ? s[0] : s[1]; rgba[i * 4 + 2] = g ? s[0] : s[2];
    rgba[i * 4 + 3] = channels === 2 ? s[1] : channels === 4 ? s[3] : 255;
  }
  return { width, height, rgba };
}

// The XML as the port's data object (tiles with bitmaps, neighbors, subsets).
function readSet(name) {
  const xml = fs.readFileSync(path.join(dataDir, name + '.xml'), 'utf8');
  const attr = (tag, key) => { const m = tag.match(new RegExp(`${key}="([^"]*)"`)); return m ? m[1] : undefined; };
  const data = { tilesize: 0, tiles: [], neighbors: [], subsets: {} };
  const tilesPart = xml.split('<tiles>')[1].split('</tiles>')[0];
  for (const t of tilesPart.match(/<tile [^>]*>/g)) {
    const img = readPng(path.join(dataDir, name, attr(t, 'name') + '.png'));
    data.tilesize = img.width;
    data.tiles.push({ name: attr(t, 'name'), symmetry: attr(t, 'symmetry') || 'X',
                      weight: Number(attr(t, 'weight') || 1), bitmap: img.rgba });
  }
  for (const n of xml.match(/<neighbor [^>]*>/g)) data.neighbors.push({ left: attr(n, 'left'), right: attr(n, 'right') });
  const subsets = xml.split('<subsets>')[1];
  if (subsets)
    for (const s of subsets.match(/<subset name="[^"]*">[\s\S]*?<\/subset>/g))
      data.subsets[attr(s, 'name')] = s.match(/<tile [^>]*>/g).map((t) => attr(t, 'name'));
  return data;
}

const cardinality = { L: 4, T: 4, I: 2, '\\': 2, F: 8, X: 1 };
let failures = 0;
function fail(msg) { console.error('FAIL ' + msg); failures++; }

function check(setName, subset, size, periodic, seed, cellsFile, fixedExpect) {
  const data = readSet(setName);
  const base = path.join(tmp, `${setName}-${subset || 'all'}-${size}-${seed}`);
  const args = ['fill', '--set', path.join(dataDir, setName + '.xml'), '--size', `${size}x${size}`, '--seed', String(seed),
                '--map-json', base + '.json', '--png', base + '.png', '--json', '--quiet'];
  if (subset) args.push('--subset', subset);
  if (periodic) args.push('--torus');
  if (cellsFile) args.push('--cells', cellsFile);
  const out = JSON.parse(execFileSync(tilekit, args, { encoding: 'utf8' }));
  const where = `${setName}/${subset || 'all'} ${size}x${size} seed ${seed}`;
  if (!out.found || !out.valid) return fail(`${where}: not filled`);
  const model = new wfc.SimpleTiledModel(data, subset || null, size, size, periodic);
  // the port's tile numbers: tiles in XML order (subset only), each expanded by its cardinality
  const first = {};
  let T = 0;
  for (const t of data.tiles) {
    if (subset && data.subsets[subset].indexOf(t.name) === -1) continue;
    first[t.name] = T; T += cardinality[t.symmetry];
  }
  if (T !== model.T) return fail(`${where}: ${T} orientations, the port has ${model.T}`);
  const map = JSON.parse(fs.readFileSync(base + '.json', 'utf8'));
  const id = map.names.map((n) => { const [name, k] = n.split(' '); return first[name] + Number(k); });
  const cell = (x, y) => id[map.cells[y][x]];
  const DX = [-1, 0, 1, 0], DY = [0, 1, 0, -1];
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++)
      for (let d = 0; d < 4; d++) {
        let x2 = x + DX[d], y2 = y + DY[d];
        if (!periodic && (x2 < 0 || y2 < 0 || x2 >= size || y2 >= size)) continue;
        x2 = (x2 + size) % size; y2 = (y2 + size) % size;
        if (model.propagator[d][cell(x, y)].indexOf(cell(x2, y2)) === -1)
          return fail(`${where}: cells (${x},${y}) and (${x2},${y2}) are not neighbours in the port`);
      }
  // the picture: the port draws the same map
  model.observed = new Array(size * size);
  for (let y = 0; y < size; y++) for (let x = 0; x < size; x++) model.observed[x + y * size] = cell(x, y);
  model.generationComplete = true;
  const theirs = model.graphics();
  const ours = readPng(base + '.png');
  if (ours.width !== size * data.tilesize || ours.height !== size * data.tilesize)
    return fail(`${where}: picture ${ours.width}x${ours.height}`);
  for (let i = 0; i < theirs.length; i++)
    if (theirs[i] !== ours.rgba[i]) return fail(`${where}: picture differs from the port's at byte ${i}`);
  if (fixedExpect)
    for (const [x, y, name] of fixedExpect)
      if (map.names[map.cells[y][x]] !== name) return fail(`${where}: fixed cell (${x},${y}) is ${map.names[map.cells[y][x]]}`);
  return true;
}

// The reference's sizes and periodicity (its samples.xml).
const samples = [
  ['Castle', '', 50, false], ['Circuit', 'Turnless', 34, true], ['Circuit', '', 34, true], ['Rooms', '', 30, false],
  ['Knots', 'Standard', 24, true], ['Knots', 'Dense', 24, true], ['Knots', 'CE', 24, true], ['Knots', 'C', 24, true],
  ['Knots', 'Fabric', 24, true], ['Knots', 'Dense Fabric', 24, true], ['Knots', 'Crossless', 24, false],
  ['Knots', 'TE', 24, false], ['Knots', 'T', 24, false], ['Knots', 'CL', 24, false],
];
let checked = 0;
for (const [set, subset, size, periodic] of samples)
  for (let seed = 1; seed <= seeds; seed++) if (check(set, subset, size, periodic, seed) === true) checked++;
// fixed cells: a path of crosses and corners painted into a Knots map
const cells = path.join(tmp, 'knots.cells');
const rows = [];
for (let y = 0; y < 12; y++) rows.push(Array(12).fill('.'));
rows[3][2] = 'corner:1'; rows[5][5] = 'cross'; rows[8][9] = 'line:1'; rows[0][0] = 'empty';
fs.writeFileSync(cells, rows.map((r) => r.join(' ')).join('\n') + '\n');
if (check('Knots', 'Standard', 12, true, 1, cells, [[2, 3, 'corner 1'], [5, 5, 'cross 0'], [9, 8, 'line 1'], [0, 0, 'empty 0']]) === true)
  checked++;
console.log(`${checked} fills checked against the npm port, ${failures} failures`);
process.exit(failures ? 1 : 0);
