// Shared helpers of the browser and load tests of `dnurbs serve` (docs/serve.md): command line
// options, starting and stopping the server, a headless Chromium, a WebSocket client, checks.

import { spawn } from 'node:child_process';
import fs from 'node:fs';
import WebSocket from 'ws';

export const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

// `--name value` options of the command line; flags without a value are not used.
export function options(defaults, usage) {
  const args = process.argv.slice(2);
  const result = { ...defaults };
  for (let i = 0; i < args.length; i++) {
    const name = args[i].replace(/^--/, '');
    if (!args[i].startsWith('--') || !(name in defaults) || i + 1 >= args.length) {
      console.error(`unknown or incomplete option ${args[i]}\n${usage}`);
      process.exit(2);
    }
    result[name] = typeof defaults[name] === 'number' ? Number(args[++i]) : args[++i];
  }
  for (const [name, value] of Object.entries(result)) {
    if (value === null || Number.isNaN(value)) {
      console.error(`--${name} is required\n${usage}`);
      process.exit(2);
    }
  }
  return result;
}

// Prints each check as `ok` or `FAIL` with its measured numbers and counts the failures.
export class Checks {
  constructor(name) {
    this.name = name;
    this.failures = 0;
    this.count = 0;
  }

  check(ok, what) {
    this.count++;
    if (!ok) this.failures++;
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
    return ok;
  }

  // Prints the summary and exits 0 when every check passed, else 1.
  finish() {
    console.log(this.failures === 0 ? `${this.name}: all ${this.count} checks passed`
                                    : `${this.name}: ${this.failures} of ${this.count} checks failed`);
    process.exit(this.failures === 0 ? 0 : 1);
  }
}

// Starts `dnurbs serve --port 0 ...extra` and resolves once it prints its address:
// { child, pid, url, port, exited: Promise<{code, signal}>, stop(ms) }.
export function startServer(dnurbs, extra) {
  return new Promise((resolve, reject) => {
    const child = spawn(dnurbs, ['serve', '--port', '0', ...extra],
                        { stdio: ['ignore', 'pipe', 'inherit'] });
    const exited = new Promise((done) => child.on('exit', (code, signal) => done({ code, signal })));
    let text = '';
    let started = false;
    child.stdout.on('data', (chunk) => {
      text += chunk;
      const firstLine = text.split('\n')[0];
      const match = text.includes('\n') && firstLine.match(/(http:\/\/[^/\s]+:(\d+)\/)/);
      if (match && !started) {
        started = true;
        // SIGTERM, then the exit status and how long it took (SIGKILL after `ms`)
        const stop = async (ms = 5000) => {
          const begin = Date.now();
          child.kill('SIGTERM');
          const result = await Promise.race([exited, sleep(ms).then(() => null)]);
          if (result === null) {
            child.kill('SIGKILL');
            return { code: 'timeout', signal: null, ms: Date.now() - begin };
          }
          return { ...result, ms: Date.now() - begin };
        };
        resolve({ child, pid: child.pid, url: match[1], port: Number(match[2]), exited, stop,
                  firstLine });
      }
    });
    child.on('error', reject);
    exited.then(({ code, signal }) => {
      if (!started) reject(new Error(`dnurbs serve exited with ${code ?? signal}: ${text}`));
    });
  });
}

// The resident set size of a process in kB, from /proc/PID/status (VmRSS).
export function rssKb(pid) {
  const status = fs.readFileSync(`/proc/${pid}/status`, 'utf8');
  const match = status.match(/^VmRSS:\s+(\d+)\s+kB/m);
  if (!match) throw new Error(`no VmRSS in /proc/${pid}/status`);
  return Number(match[1]);
}

// Headless Chromium with WebGL through SwiftShader (software), which works without a GPU and
// as root (--no-sandbox).
export async function launchBrowser() {
  const { chromium } = await import('playwright-core');
  return chromium.launch({
    executablePath: process.env.DNURBS_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
           '--ignore-gpu-blocklist'],
  });
}

// A WebSocket client of the server: text replies parsed into `messages` (the latest status in
// `status`), binary frames counted with their arrival times; `request` sends a message with an
// id and resolves with the reply carrying that id (or an error reply).
export function connect(port) {
  return new Promise((resolve, reject) => {
    const ws = new WebSocket(`ws://127.0.0.1:${port}/ws`, { maxPayload: 64 << 20 });
    const client = { ws, messages: [], status: null, statuses: [], frames: 0, frameTimes: [],
                     closed: false, nextId: 1 };
    ws.on('message', (data, binary) => {
      if (binary) {
        client.frames++;
        client.frameTimes.push(performance.now());
        return;
      }
      const message = JSON.parse(data.toString());
      if (message.type === 'status') {
        client.status = message;
        client.statuses.push({ at: performance.now(), status: message });
      } else {
        client.messages.push(message);
      }
    });
    ws.on('close', () => { client.closed = true; });
    ws.on('open', () => resolve(client));
    ws.on('error', reject);
    client.send = (message) => ws.send(JSON.stringify(message));
    client.request = async (message, ms = 5000) => {
      const id = client.nextId++;
      client.send({ ...message, id });
      const begin = Date.now();
      while (Date.now() - begin < ms) {
        const reply = client.messages.find((m) => m.id === id);
        if (reply) return reply;
        await sleep(5);
      }
      throw new Error(`no reply to ${message.type} within ${ms} ms`);
    };
  });
}
