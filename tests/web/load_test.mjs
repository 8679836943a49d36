// Load test of `dnurbs serve` (docs/serve.md) on loopback: one client drags the hat's crown
// around a circle; phase A alone, phase B with watching clients that receive every frame too.
// The dragging client's frame rate and the server's step rate in B must be within 10% of A's,
// and the server's memory (VmRSS) must not grow during B: the mean of its last 5 one-second
// samples within 5% (or 2 MB) of the mean of its first 5.
//
// usage: node tests/web/load_test.mjs --dnurbs PATH [--seconds 30] [--clients 20]   (exit 0/1)

import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { Checks, connect, options, rssKb, sleep, startServer } from './lib.mjs';

const opts = options({ dnurbs: null, seconds: 30, clients: 20 },
                     'usage: node load_test.mjs --dnurbs PATH [--seconds 30] [--clients 20]');
const checks = new Checks('load test');
const check = checks.check.bind(checks);
const kCircleRadius = 0.3;     // the target's circle around the point above the crown
const kCircleHeight = 0.3;     // above the crown
const kCirclePeriodMs = 2000;
const kMovesPerSecond = 30;    // well under the server's 200 messages a second per client
const kWarmupMs = 1000;        // after a phase's clients connect, before measuring

const mean = (xs) => xs.reduce((a, b) => a + b, 0) / Math.max(xs.length, 1);
const relative = (b, a) => Math.abs(b - a) / Math.abs(a);

async function waitForScene(client, ms = 5000) {
  const begin = Date.now();
  while (Date.now() - begin < ms) {
    const scene = client.messages.find((m) => m.type === 'scene');
    if (scene && client.status) return scene;
    await sleep(10);
  }
  throw new Error('no scene and status within 5 s');
}

// A phase: for `seconds`, the dragging client's frame rate (frames counted over the window),
// the server's steps a second (mean of the statuses received in the window) and RSS samples.
async function measure(server, dragger, seconds, watchers) {
  const begin = performance.now();
  const samples = [];
  const firstWatcherFrames = watchers.map((w) => w.frames);
  for (let s = 0; s < seconds; s++) {
    await sleep(1000);
    samples.push(rssKb(server.pid));
  }
  const end = performance.now();
  const duration = (end - begin) / 1000;
  const frames = dragger.frameTimes.filter((t) => t >= begin && t < end).length;
  const statuses = dragger.statuses.filter((s) => s.at >= begin && s.at < end).map((s) => s.status);
  const watcherRates = watchers.map((w, i) => (w.frames - firstWatcherFrames[i]) / duration);
  return {
    fps: frames / duration,
    steps: mean(statuses.map((s) => s.steps_per_second)),
    stepMs: mean(statuses.map((s) => s.step_ms)),
    clients: statuses.at(-1)?.clients,
    rss: samples,
    watcherRates,
  };
}

const out = fs.mkdtempSync(path.join(os.tmpdir(), 'dnurbs-load-'));
const server = await startServer(opts.dnurbs, ['--out', out]).catch((error) => {
  console.log(`FAIL dnurbs serve did not start: ${error.message}`);
  fs.rmSync(out, { recursive: true, force: true });
  process.exit(1);
});
const clients = [];
let mover = null;
try {
  const dragger = await connect(server.port);
  clients.push(dragger);
  const scene = await waitForScene(dragger);
  const hat = scene.models.find((m) => m.name === 'hat').index;
  const crown = (await dragger.request({ type: 'query', model: hat, at: [0.5, 0.5] })).position;
  const centre = [crown[0], crown[1], crown[2] + kCircleHeight];
  const grabbed = await dragger.request({ type: 'grab', model: hat, at: [0.5, 0.5], target: crown });
  check(grabbed.type === 'grabbed', `the dragging client grabs the hat's crown (drag ${grabbed.drag})`);
  const started = performance.now();
  mover = setInterval(() => {
    const angle = (2 * Math.PI * (performance.now() - started)) / kCirclePeriodMs;
    dragger.send({ type: 'move', drag: grabbed.drag, target: [
      centre[0] + kCircleRadius * Math.cos(angle), centre[1] + kCircleRadius * Math.sin(angle), centre[2]] });
  }, 1000 / kMovesPerSecond);
  await sleep(kWarmupMs);

  console.log(`phase A: 1 client dragging for ${opts.seconds} s`);
  const a = await measure(server, dragger, opts.seconds, []);
  console.log(`     A: ${a.fps.toFixed(2)} frames/s received, ${a.steps.toFixed(2)} steps/s, ` +
              `step ${a.stepMs.toFixed(3)} ms, ${a.clients} client(s), RSS ${a.rss.join(' ')} kB`);

  const watchers = [];
  for (let i = 1; i < opts.clients; i++) watchers.push(await connect(server.port));
  clients.push(...watchers);
  await Promise.all(watchers.map((w) => waitForScene(w)));
  await sleep(kWarmupMs);
  console.log(`phase B: the dragging client and ${watchers.length} watching clients for ${opts.seconds} s`);
  const b = await measure(server, dragger, opts.seconds, watchers);
  console.log(`     B: ${b.fps.toFixed(2)} frames/s received, ${b.steps.toFixed(2)} steps/s, ` +
              `step ${b.stepMs.toFixed(3)} ms, ${b.clients} client(s), RSS ${b.rss.join(' ')} kB`);
  console.log(`     watchers: ${Math.min(...b.watcherRates).toFixed(2)} to ` +
              `${Math.max(...b.watcherRates).toFixed(2)} frames/s, mean ${mean(b.watcherRates).toFixed(2)}`);

  check(b.clients === opts.clients, `the server counts ${b.clients} clients in B`);
  check(a.fps > 0 && relative(b.fps, a.fps) <= 0.1,
        `dragging client's frame rate: A ${a.fps.toFixed(2)}/s, B ${b.fps.toFixed(2)}/s ` +
        `(${(100 * relative(b.fps, a.fps)).toFixed(1)}% apart, at most 10%)`);
  check(a.steps > 0 && relative(b.steps, a.steps) <= 0.1,
        `server steps a second: A ${a.steps.toFixed(2)}, B ${b.steps.toFixed(2)} ` +
        `(${(100 * relative(b.steps, a.steps)).toFixed(1)}% apart, at most 10%)`);
  check(Math.min(...b.watcherRates) > 0, 'every watching client receives frames');
  const firstRss = mean(b.rss.slice(0, 5));
  const lastRss = mean(b.rss.slice(-5));
  const growth = lastRss - firstRss;
  check(growth <= Math.max(0.05 * firstRss, 2048),
        `server RSS in B: first 5 samples ${firstRss.toFixed(0)} kB, last 5 ${lastRss.toFixed(0)} kB ` +
        `(${growth >= 0 ? '+' : ''}${growth.toFixed(0)} kB; at most 5% or 2048 kB)`);

  clearInterval(mover);
  mover = null;
  const released = await dragger.request({ type: 'release', drag: grabbed.drag });
  check(released.type === 'released', 'the drag is released');
} catch (error) {
  check(false, `the test ran to its end: ${error.stack}`);
} finally {
  if (mover) clearInterval(mover);
  for (const c of clients) c.ws.close();
  await sleep(200);
  const stopped = await server.stop(5000);
  check(stopped.code === 0, `SIGTERM stops the server with exit code ${stopped.code} in ${stopped.ms} ms`);
  fs.rmSync(out, { recursive: true, force: true });
}
checks.finish();
