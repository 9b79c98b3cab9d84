// The preview page's JavaScript ports (render/preview_tables.js, the file `texture preview` embeds)
// against the golden vectors of tests/render/preview_golden.json, which
// tests/render/test_preview_golden.cpp checks the C++ against: SplitMix64, Lemire's below,
// derive_seed, FNV-1a and the seeded permutation tables. Then, so that the test can fail, each
// section again with one expected value changed: every such copy must be reported as wrong.
// Usage: node tests/render/preview_golden.test.js [REPOSITORY_ROOT]; exit 0 when all pass.
'use strict';
const fs = require('fs');
const path = require('path');

const root = process.argv[2] || path.join(__dirname, '..', '..');
const port = require(path.join(root, 'render', 'preview_tables.js'));
const golden = JSON.parse(fs.readFileSync(path.join(root, 'tests', 'render', 'preview_golden.json'), 'utf8'));

// The failures of every vector of `g`, one line each.
function failures(g) {
  const out = [];
  const expect = (name, got, want) => {
    const a = JSON.stringify(got), b = JSON.stringify(want);
    if (a !== b) out.push(name + ': got ' + a + ', want ' + b);
  };
  for (const v of g.splitmix64) {
    const r = new port.Rng(BigInt(v.seed));
    expect('splitmix64 seed ' + v.seed, v.outputs.map(() => r.next().toString()), v.outputs);
  }
  for (const v of g.below) {
    const r = new port.Rng(BigInt(v.seed));
    expect('below seed ' + v.seed + ' n ' + v.n, v.outputs.map(() => r.below(v.n)), v.outputs);
  }
  for (const v of g.derive_seed)
    expect('derive_seed ' + v.seed + ' ' + v.stream, port.derive(BigInt(v.seed), v.stream).toString(), v.value);
  for (const v of g.fnv1a) {
    const bytes = v.bytes || [...Buffer.from(v.text, 'latin1')];
    expect('fnv1a ' + JSON.stringify(v.text ?? v.bytes), port.fnv(bytes), v.hash);
  }
  for (const v of g.tables)
    expect('table ' + JSON.stringify(v.builder) + ' seed ' + v.seed, Array.from(port.hashTable(v.recipe, BigInt(v.seed))),
           v.table);
  return out;
}

let failed = 0;
const found = failures(golden);
for (const line of found) console.log('FAIL: ' + line);
failed += found.length;
const counts = ['splitmix64', 'below', 'derive_seed', 'fnv1a', 'tables'].map(k => golden[k].length);
if (counts.some(n => n === 0)) {
  console.log('FAIL: a section of the golden vectors is empty: ' + counts.join(', '));
  ++failed;
}

// One wrong expected value per section must be caught.
const corruptions = {
  splitmix64: v => { v.outputs[1] = (BigInt(v.outputs[1]) ^ 1n).toString(); },
  below: v => { v.outputs[2] = (v.outputs[2] + 1) % v.n; },
  derive_seed: v => { v.value = (BigInt(v.value) ^ (1n << 63n)).toString(); },
  fnv1a: v => { v.hash = (BigInt(v.hash) + 1n).toString(); },
  tables: v => { [v.table[0], v.table[1]] = [v.table[1], v.table[0]]; },
};
for (const [section, corrupt] of Object.entries(corruptions)) {
  const copy = JSON.parse(JSON.stringify(golden));
  corrupt(copy[section][0]);
  if (failures(copy).length <= found.length) {
    console.log('FAIL: a wrong ' + section + ' vector is not reported');
    ++failed;
  }
}
const total = counts.reduce((a, b) => a + b, 0);
console.log(failed ? failed + ' failed' : total + ' golden vectors passed; each section fails when one value is wrong');
process.exit(failed ? 1 : 0);
