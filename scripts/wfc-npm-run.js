// One sample of the WFC benchmark (scripts/bench-fill-vs-wfc.py) run by the npm port of the
// reference (wavefunctioncollapse): for each seed, generate() in slices until the map is complete,
// starting again after a contradiction (as the reference does), within a time limit per seed.
// Usage: NODE_PATH=$(scripts/npm-deps.sh)/node_modules node scripts/wfc-npm-run.js XML SUBSET SIZE PERIODIC(0|1) SEED0 SEEDS LIMIT_S
// Prints one JSON object: {"runs": [{"seed", "ok", "seconds", "attempts"}], "counts": [cells per tile over the successes]}.
'use strict';
const fs = require('fs');
const path = require('path');
const wfc = require('wavefunctioncollapse');

const [xmlPath, subset, sizeArg, periodicArg, seed0Arg, seedsArg, limitArg] = process.argv.slice(2);
const size = Number(sizeArg), periodic = periodicArg === '1', limit = Number(limitArg);
const xml = fs.readFileSync(xmlPath, 'utf8');
const attr = (tag, key) => { const m = tag.match(new RegExp(`${key}="([^"]*)"`)); return m ? m[1] : undefined; };
// generation does not look at the pictures: each tile gets a blank bitmap of the size the port needs
const data = { tilesize: 1, tiles: [], neighbors: [], subsets: {} };
for (const t of xml.split('<tiles>')[1].split('</tiles>')[0].match(/<tile [^>]*>/g))
  data.tiles.push({ name: attr(t, 'name'), symmetry: attr(t, 'symmetry') || 'X', weight: Number(attr(t, 'weight') || 1),
                    bitmap: new Uint8Array(4) });
for (const n of xml.match(/<neighbor [^>]*>/g)) data.neighbors.push({ left: attr(n, 'left'), right: attr(n, 'right') });
const subs = xml.split('<subsets>')[1];
if (subs) for (const s of subs.match(/<subset name="[^"]*">[\s\S]*?<\/subset>/g))
  data.subsets[attr(s, 'name')] = s.match(/<tile [^>]*>/g).map((t) => attr(t, 'name'));

function mulberry32(a) {  // a seeded generator for Math.random's place
  return function () {
    a |= 0; a = (a + 0x6d2b79f5) | 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const runs = [];
let counts = null;
for (let k = 0; k < Number(seedsArg); k++) {
  const seed = Number(seed0Arg) + k;
  const rng = mulberry32(seed);
  const t0 = process.hrtime.bigint();
  const secs = () => Number(process.hrtime.bigint() - t0) / 1e9;
  const model = new wfc.SimpleTiledModel(data, subset || null, size, size, periodic);
  let attempts = 0, ok = false;
  while (!ok && secs() < limit) {
    if (!model.wave) model.initialize();
    model.clear();
    attempts++;
    for (;;) {
      const alive = model.iterate(200, rng);
      if (model.isGenerationComplete()) { ok = true; break; }
      if (!alive || secs() >= limit) break;
    }
  }
  const seconds = secs();
  if (ok) {
    if (!counts) counts = new Array(model.T).fill(0);
    for (const t of model.observed) counts[t]++;
  }
  runs.push({ seed, ok, seconds, attempts });
}
process.stdout.write(JSON.stringify({ runs, counts }) + '\n');
