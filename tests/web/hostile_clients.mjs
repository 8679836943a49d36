// Hostile clients against a real `dnurbs serve` (no browser): malformed and oversized messages,
// binary frames, a flood, raw garbage on the socket, path tricks over HTTP and a client killed
// mid-drag. The server must answer each bad message with an error (or close only the offending
// connection), keep serving everyone else, leave no spring behind, write nothing outside its
// output folder and exit 0 on SIGTERM. CI runs it against the release build (ctest web) and the
// AddressSanitizer build (scripts/sanitize_check.sh).
//
// usage: node tests/web/hostile_clients.mjs --dnurbs PATH [--out DIR]

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import net from 'node:net';
import os from 'node:os';
import path from 'node:path';
import WebSocket from 'ws';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const dnurbs = option('--dnurbs', null);
if (!dnurbs) {
  console.error('usage: node hostile_clients.mjs --dnurbs PATH [--out DIR]');
  process.exit(2);
}
const root = fs.mkdtempSync(path.join(os.tmpdir(), 'dnurbs-hostile-'));
const out = option('--out', path.join(root, 'out'));

let failures = 0;
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures++;
};
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Starts the server; resolves with its port once it prints its address.
function start() {
  return new Promise((resolve, reject) => {
    const server = spawn(dnurbs, ['serve', '--port', '0', '--out', out, '--resolution', '8'],
                         { stdio: ['ignore', 'pipe', 'inherit'] });
    let text = '';
    server.stdout.on('data', (chunk) => {
      text += chunk;
      const match = text.match(/http:\/\/127\.0\.0\.1:(\d+)\//);
      if (match) resolve({ server, port: Number(match[1]) });
    });
    server.on('exit', (code) => reject(new Error(`server exited early with ${code}: ${text}`)));
  });
}

// A client that records every text reply and counts binary frames.
function client(port) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(`ws://127.0.0.1:${port}/ws`, { maxPayload: 64 << 20 });
    const c = { ws, replies: [], frames: 0, closed: false };
    ws.on('message', (data, binary) => {
      if (binary) c.frames++;
      else c.replies.push(JSON.parse(data.toString()));
    });
    ws.on('close', () => { c.closed = true; });
    ws.on('open', () => resolve(c));
    ws.on('error', reject);
  });
}

const errors = (c) => c.replies.filter((m) => m.type === 'error');
const last = (c, type) => c.replies.filter((m) => m.type === type).at(-1);

// Sends `message` with a fresh id; resolves with the reply of `type` or the error of that id
// (other errors, such as a report of dropped messages, are not this request's).
let nextId = 1;
async function request(c, message, type) {
  const before = c.replies.length;
  const id = nextId++;
  c.ws.send(JSON.stringify({ ...message, id }));
  for (let i = 0; i < 100; i++) {
    const reply = c.replies.slice(before).find(
      (m) => (m.type === type && (m.id === undefined || m.id === id)) || (m.type === 'error' && m.id === id));
    if (reply) return reply;
    await sleep(20);
  }
  return null;
}

function http(port, raw) {
  return new Promise((resolve) => {
    const socket = net.connect(port, '127.0.0.1', () => socket.end(raw));
    let text = '';
    socket.on('data', (d) => { text += d; });
    socket.on('close', () => resolve(text));
    socket.on('error', () => resolve(text));
  });
}

const { server, port } = await start();
const exited = new Promise((resolve) => server.on('exit', (code, signal) => resolve({ code, signal })));
try {
  const a = await client(port);
  await sleep(300);
  check(a.replies[0]?.type === 'scene', 'a client gets the scene first');
  a.ws.send(JSON.stringify({ type: 'pause' }));
  await sleep(200);
  const paused = await request(a, { type: 'query', model: 0, at: [0.5, 0.5] }, 'point');

  // Malformed messages: one error each, nothing changed
  const bad = [
    'garbage', '{"type":', '[]', 'null', '{"type":"grab"}', '{"type":"set","key":"dt","value":"0.1"}',
    '{"type":"grab","model":0,"at":[0.5,0.5],"target":[0,0,1e308],"x":1}',
    '{"type":"move","drag":12345,"target":[0,0,0]}', '{"type":"release","drag":-1}',
    '{"type":"set","key":"__proto__","value":1}', '{"type":"\u0000\u202e"}',
    JSON.stringify({ type: 'pin', model: 0, at: [0.5, Number.MAX_VALUE] }),
    'x'.repeat(20000),
  ];
  const errorsBefore = errors(a).length;
  for (const message of bad) a.ws.send(message);
  await sleep(500);
  check(errors(a).length - errorsBefore === bad.length,
        `${bad.length} malformed messages, ${errors(a).length - errorsBefore} error replies`);
  const after = await request(a, { type: 'query', model: 0, at: [0.5, 0.5] }, 'point');
  check(JSON.stringify(after?.position) === JSON.stringify(paused?.position),
        'the paused state is unchanged by them');

  // A binary message is refused with an error; a message over the socket limit closes only
  // that connection
  a.ws.send(Buffer.from([1, 2, 3]));
  await sleep(200);
  check(/binary/.test(errors(a).at(-1)?.message ?? ''), 'a binary message gets an error');
  const big = await client(port);
  big.ws.send('{"type":"play","pad":"' + 'y'.repeat(200000) + '"}');
  await sleep(500);
  check(big.closed, 'a 200 kB message closes its connection');

  // A flood: most refused, the server still answers
  const flooder = await client(port);
  for (let i = 0; i < 5000; i++) flooder.ws.send('{"type":"pause"}');
  await sleep(1500);
  const floodErrors = errors(flooder).filter((m) => /too many|dropped/.test(m.message)).length;
  check(floodErrors >= 1 && floodErrors <= 20, `a flood of 5000 gets ${floodErrors} warnings`);
  const answered = await request(flooder, { type: 'query', model: 0, at: [0.5, 0.5] }, 'point');
  check(answered?.type === 'point', 'the flooder is answered again after the flood');

  // A client killed mid-drag leaves no spring
  const dragger = await client(port);
  const grabbed = await request(dragger, { type: 'grab', model: 0, at: [0.5, 0.5], target: [0, 0, 0.5] }, 'grabbed');
  check(grabbed?.type === 'grabbed', 'a grab is answered');
  await sleep(300);
  check(last(a, 'status')?.drags === 1, 'the other clients see one drag');
  dragger.ws.terminate();
  await sleep(800);
  check(last(a, 'status')?.drags === 0, 'the drag is gone when its client is killed');

  // Raw garbage and path tricks over HTTP
  const garbage = await http(port, 'GARBAGE\r\n\r\n');
  check(/^HTTP\/1\.1 400/.test(garbage), 'a garbage request gets 400');
  for (const target of ['/../../etc/passwd', '/%2e%2e/%2e%2e/etc/passwd', '/three/../../etc/passwd',
                        '/.hidden.js', '/web/index.html']) {
    const reply = await http(port, `GET ${target} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n`);
    check(/^HTTP\/1\.1 404/.test(reply) && !reply.includes('root:'), `GET ${target} is 404`);
  }
  const huge = await http(port, `GET / HTTP/1.1\r\nHost: x\r\nX: ${'z'.repeat(20000)}\r\n\r\n`);
  check(/^HTTP\/1\.1 413/.test(huge), 'a 20 kB header gets 413');
  const foreign = await new Promise((resolve) => {
    const ws = new WebSocket(`ws://127.0.0.1:${port}/ws`, { origin: 'http://evil.example' });
    ws.on('open', () => resolve('open'));
    ws.on('unexpected-response', (_, response) => resolve(response.statusCode));
    ws.on('error', () => resolve('error'));
  });
  check(foreign === 403, `a page of another origin is refused (${foreign})`);

  // Saving writes only into the output folder
  const saved = await request(a, { type: 'save' }, 'saved');
  const files = saved?.files ?? [];
  check(files.length > 0 && files.every((f) => path.dirname(path.resolve(f)) === path.resolve(out)),
        `save wrote ${files.length} files, all in the output folder`);

  // Everyone else was served throughout: a fresh client gets the scene and frames
  const fresh = await client(port);
  await sleep(500);
  check(fresh.replies[0]?.type === 'scene' && fresh.frames > 0, 'a fresh client is served');
} finally {
  server.kill('SIGTERM');
}
const { code, signal } = await Promise.race([exited, sleep(5000).then(() => ({ code: 'timeout' }))]);
check(code === 0, `SIGTERM stops the server with exit code ${code}${signal ? ` (${signal})` : ''}`);
fs.rmSync(root, { recursive: true, force: true });
console.log(failures === 0 ? 'hostile clients: all passed' : `hostile clients: ${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
