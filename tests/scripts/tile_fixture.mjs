// What the node tests of Tilekit's outputs in the users' tools share: a 96x96 exemplar with
// structure at every scale, written as a PNG, and its corner tile set (C = 2, 16-pixel tiles).
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import zlib from 'node:zlib';

export function png(w, h, rgb) {
  const crc = b => { let c = ~0; for (const x of b) { c ^= x; for (let k = 0; k < 8; ++k) c = (c >>> 1) ^ (0xEDB88320 & -(c & 1)); } return ~c >>> 0; };
  const chunk = (type, data) => {
    const b = Buffer.alloc(12 + data.length);
    b.writeUInt32BE(data.length, 0); b.write(type, 4, 'latin1'); data.copy(b, 8);
    b.writeUInt32BE(crc(b.subarray(4, 8 + data.length)), 8 + data.length);
    return b;
  };
  const raw = Buffer.alloc(h * (1 + 3 * w));
  for (let y = 0; y < h; ++y) for (let x = 0; x < w; ++x) rgb(x, y).forEach((v, c) => { raw[y * (1 + 3 * w) + 1 + 3 * x + c] = v; });
  const ihdr = Buffer.alloc(13); ihdr.writeUInt32BE(w, 0); ihdr.writeUInt32BE(h, 4); ihdr[8] = 8; ihdr[9] = 2;
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr), chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}

// `run(args)`: tilekit's stdout; the tile set in dir/t.
export function tileSet(tilekit, dir) {
  const run = args => execFileSync(tilekit, args, { stdio: ['ignore', 'pipe', 'inherit'] }).toString();
  fs.writeFileSync(path.join(dir, 'ex.png'), png(96, 96, (x, y) => [(x * 7 + y * 3) % 256, (x * y) % 256, ((x ^ y) * 2) % 256]));
  run(['texture', 'tiles', '--exemplar', path.join(dir, 'ex.png'), '--colors', '2', '--tile-px', '16', '--search', '2', '--out', path.join(dir, 't'), '--quiet']);
  return run;
}

// The page's comparison of a W x H RGBA capture (rows from the top) with a PNG's pixels: the
// largest difference over R, G and B. Text of a function for the page's script.
export const pageCompare = `
async function largestDifference(px, pngBytes, w, h) {
  const bitmap = await createImageBitmap(new Blob([pngBytes], { type: 'image/png' }), { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
  const ctx = new OffscreenCanvas(w, h).getContext('2d');
  ctx.drawImage(bitmap, 0, 0);
  const ref = ctx.getImageData(0, 0, w, h).data;
  let worst = 0;
  for (let i = 0; i < w * h * 4; ++i) if (i % 4 !== 3) worst = Math.max(worst, Math.abs(px[i] - ref[i]));
  return worst;
}`;
