// Opens a local page in Debian's chromium, headless, and returns the value of the promise the page
// stores in `window.tkResult` (through the DevTools protocol: node 20's WebSocket, started with
// --experimental-websocket). WebGL2 runs on SwiftShader (as scripts/capture-preview.sh), WebGPU on
// SwiftShader's Vulkan (`webgpu: true`). The network stays off; the page may read files beside it.
//   import { evaluatePage } from './chromium_eval.mjs';
//   const value = await evaluatePage('/tmp/x/page.html', { webgpu: false, seconds: 120 });
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const sleep = ms => new Promise(r => setTimeout(r, ms));

// `expression` (default window.tkResult) is evaluated until it is not undefined; `query` is appended
// to the page's URL.
// `page` is a file, or a URL (http://...).
export async function evaluatePage(page, { webgpu = false, seconds = 120, expression = 'window.tkResult', query = '' } = {}) {
  const browser = process.env.TILEKIT_CHROMIUM || 'chromium';
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'tk-chromium-'));
  const gpuFlags = webgpu
    ? ['--enable-unsafe-webgpu', '--enable-features=Vulkan', '--use-vulkan=swiftshader', '--disable-vulkan-surface']
    : ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'];
  // --no-sandbox: root in a container has no user namespaces for chromium's sandbox; the page is ours.
  const args = ['--headless=new', ...gpuFlags, '--no-sandbox', '--no-first-run', '--no-default-browser-check',
    '--disable-background-networking', '--disable-component-update', '--disable-sync', '--disable-extensions',
    '--disable-default-apps', '--metrics-recording-only', '--no-pings', '--mute-audio', '--allow-file-access-from-files',
    '--remote-debugging-port=0', `--user-data-dir=${profile}`, '--window-size=400,400', 'about:blank'];
  const child = spawn(browser, args, { stdio: ['ignore', 'ignore', 'pipe'] });
  let log = '';
  child.stderr.on('data', d => { log += d; });
  const deadline = Date.now() + seconds * 1000;
  const timeout = what => { throw new Error(`${browser}: ${what} within ${seconds} s; its log:\n${log}`); };
  try {
    let port;
    while (!port) {
      if (Date.now() > deadline) timeout('no DevTools port');
      if (child.exitCode !== null) throw new Error(`${browser} exited (${child.exitCode}); its log:\n${log}`);
      try { port = fs.readFileSync(path.join(profile, 'DevToolsActivePort'), 'utf8').split('\n')[0]; } catch { await sleep(100); }
    }
    const targets = await (await fetch(`http://127.0.0.1:${port}/json/list`)).json();
    const ws = new WebSocket(targets.find(t => t.type === 'page').webSocketDebuggerUrl);
    await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
    let id = 0;
    const pending = new Map();
    let loaded;
    const load = new Promise(r => { loaded = r; });
    ws.onmessage = m => {
      const msg = JSON.parse(m.data);
      if (msg.id && pending.has(msg.id)) { pending.get(msg.id)(msg); pending.delete(msg.id); }
      if (msg.method === 'Page.loadEventFired') loaded();
    };
    const send = (method, params = {}) => new Promise(resolve => {
      pending.set(++id, resolve);
      ws.send(JSON.stringify({ id, method, params }));
    });
    await send('Page.enable');
    const url = /^https?:/.test(page) ? page : 'file://' + path.resolve(page);
    await send('Page.navigate', { url: url + query });
    // the page's load, not about:blank's (an unref'd timer: it must not keep node alive afterwards)
    await Promise.race([load, new Promise(r => setTimeout(r, Math.max(0, deadline - Date.now())).unref())]);
    for (;;) {
      if (Date.now() > deadline) timeout('no window.tkResult');
      const r = await send('Runtime.evaluate', {
        expression, awaitPromise: true, returnByValue: true,
      });
      if (r.result && r.result.exceptionDetails) throw new Error('the page threw: ' + JSON.stringify(r.result.exceptionDetails));
      if (r.result && r.result.result && r.result.result.type !== 'undefined') {
        ws.close();
        return r.result.result.value;
      }
      await sleep(200);
    }
  } finally {
    if (child.exitCode === null) {
      const exited = new Promise(r => child.once('exit', r));
      child.kill('SIGTERM');
      await Promise.race([exited, sleep(5000)]);
      if (child.exitCode === null) child.kill('SIGKILL');
    }
    try { fs.rmSync(profile, { recursive: true, force: true, maxRetries: 10, retryDelay: 200 }); } catch { /* a helper still exiting */ }
  }
}
