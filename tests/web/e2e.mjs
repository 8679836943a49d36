// The sculpting page of `dnurbs serve` (docs/serve.md) in a headless Chromium: it loads without
// console errors, renders the scene's frames, rejects malformed messages without changing
// anything, and a scripted mouse drag on the hat pulls its crown to the target that the camera's
// projection predicts; `save` writes the hat's exact shape; a screenshot is not blank.
//
// usage: node tests/web/e2e.mjs --dnurbs PATH/TO/dnurbs --out DIR     (exit 0 pass, 1 fail)

import fs from 'node:fs';
import path from 'node:path';
import { PNG } from 'pngjs';
import { Checks, launchBrowser, options, sleep, startServer } from './lib.mjs';

const opts = options({ dnurbs: null, out: null },
                     'usage: node e2e.mjs --dnurbs PATH/TO/dnurbs --out DIR');
const out = path.resolve(opts.out);
fs.mkdirSync(out, { recursive: true });
const checks = new Checks('e2e');
const check = checks.check.bind(checks);

const kDragPixels = 80;      // the scripted drag moves the cursor this far up the screen
const kDragMoves = 10;       // in this many mouse moves
const kStiffness = 1e4;      // the mouse spring's stiffness during the drag
const kDamping = 100;        // damping density during the drag: settles in seconds (equilibrium
                             // does not depend on damping)
const kSettleLimitMs = 30000;

const vec = {
  sub: (a, b) => a.map((x, i) => x - b[i]),
  add: (a, b) => a.map((x, i) => x + b[i]),
  scale: (a, s) => a.map((x) => x * s),
  dot: (a, b) => a.reduce((sum, x, i) => sum + x * b[i], 0),
  norm: (a) => Math.hypot(...a),
};

// The largest difference between two JSON values of the same structure, in the numbers under
// `key` (null when the structures or any non-number differ).
function numberDifferences(a, b, key = '', into = {}) {
  if (typeof a === 'number' && typeof b === 'number') {
    into[key] = Math.max(into[key] ?? 0, Math.abs(a - b));
    into[`${key}:scale`] = Math.max(into[`${key}:scale`] ?? 0, Math.abs(a), Math.abs(b));
    return into;
  }
  if (Array.isArray(a) && Array.isArray(b) && a.length === b.length) {
    a.forEach((x, i) => numberDifferences(x, b[i], key, into));
    return into;
  }
  if (a && b && typeof a === 'object' && typeof b === 'object' && !Array.isArray(a) && !Array.isArray(b)) {
    const keys = Object.keys(a).sort();
    if (JSON.stringify(keys) !== JSON.stringify(Object.keys(b).sort())) return null;
    for (const k of keys) if (numberDifferences(a[k], b[k], k, into) === null) return null;
    return into;
  }
  return a === b ? into : null;
}

async function waitFor(page, predicate, arg, ms, what) {
  try {
    await page.waitForFunction(predicate, arg, { timeout: ms, polling: 50 });
    return true;
  } catch (error) {
    console.log(`     (timed out after ${ms} ms waiting for ${what})`);
    return false;
  }
}

const server = await startServer(opts.dnurbs, ['--out', out]).catch((error) => {
  console.log(`FAIL dnurbs serve did not start: ${error.message}`);
  process.exit(1);
});
check(/^dnurbs serve: listening on http:\/\/127\.0\.0\.1:\d+\//.test(server.firstLine),
      `the first line gives the loopback address: "${server.firstLine}"`);
const browser = await launchBrowser();
const consoleErrors = [];
const consoleWarnings = [];
try {
  const page = await browser.newPage({ viewport: { width: 1200, height: 800 } });
  page.on('console', (m) => {
    if (m.type() === 'error') consoleErrors.push(m.text());
    if (m.type() === 'warning') consoleWarnings.push(m.text());
  });
  page.on('pageerror', (e) => consoleErrors.push(`pageerror: ${e.message}`));
  const request = (message) => page.evaluate((m) => window.dnurbs.request(m), message);
  const dnurbs = (expression) => page.evaluate(expression);

  // Loading: the scene, frames received and rendered
  const begin = Date.now();
  await page.goto(server.url);
  const loaded = await waitFor(page, () => window.dnurbs && window.dnurbs.scene &&
                               window.dnurbs.status && window.dnurbs.framesReceived > 0,
                               null, 20000, 'the scene and a frame');
  check(loaded, `the scene, a frame and a status arrive (${Date.now() - begin} ms)`);
  await sleep(2000);
  const first = await dnurbs(() => ({
    models: window.dnurbs.scene.models.map((m) => m.name), frames: window.dnurbs.framesReceived,
    renderFps: window.dnurbs.renderFps, receivedFps: window.dnurbs.receivedFps,
    meshes: window.dnurbs.meshes.length, status: document.getElementById('status').textContent }));
  check(first.meshes === first.models.length && first.models.includes('hat'),
        `one mesh per model: ${first.meshes} meshes for ${first.models.join(', ')}`);
  check(first.frames > 10 && first.receivedFps > 10,
        `frames arrive: ${first.frames} so far, ${first.receivedFps} in the last second`);
  check(first.renderFps > 0, `frames are rendered: ${first.renderFps} a second`);
  console.log(`     status line: ${first.status}`);
  const hat = await dnurbs(() => window.dnurbs.scene.models.find((m) => m.name === 'hat').index);

  // Malformed messages through the page's socket, while paused: one error reply each, and
  // neither the step nor the hat's shape changes
  await request({ type: 'pause' });
  await sleep(300);
  const before = await dnurbs(() => ({ step: window.dnurbs.status.step, errors: window.dnurbs.errors.length }));
  const shapeBefore = await request({ type: 'shape', model: hat });
  const malformed = [
    'this is not JSON',
    JSON.stringify({ type: 'frobnicate' }),
    '{"type":"grab","model":0,"at":[0.5,0.5],"target":["1e400",0,0]}',
    '{"type":"set","key":"stiffness","value":"NaN"}',
  ];
  for (const text of malformed) await page.evaluate((t) => window.dnurbs.sendRaw(t), text);
  await waitFor(page, (n) => window.dnurbs.errors.length >= n, before.errors + malformed.length,
                3000, 'the error replies');
  await sleep(500);
  const after = await dnurbs(() => ({ step: window.dnurbs.status.step, errors: window.dnurbs.errors,
                                      drags: window.dnurbs.status.drags }));
  const replies = after.errors.slice(before.errors);
  check(replies.length === malformed.length,
        `${malformed.length} malformed messages, ${replies.length} error replies`);
  for (const reply of replies) console.log(`     error: ${reply.message}`);
  const shapeAfter = await request({ type: 'shape', model: hat });
  check(after.step === before.step && after.drags === 0,
        `paused: the step stays ${before.step} (now ${after.step}), no drag (${after.drags})`);
  check(JSON.stringify(shapeAfter.shape) === JSON.stringify(shapeBefore.shape),
        'the hat\'s shape is unchanged by them');
  const rejected = await request({ type: 'frobnicate' }).then(() => 'resolved',
                                                               (e) => e.message.split('\n')[0]);
  check(rejected !== 'resolved', `request() rejects on an error reply: "${rejected}"`);
  await request({ type: 'play' });

  // The drag: stiff spring, settle fast
  await request({ type: 'set', key: 'stiffness', value: kStiffness });
  await request({ type: 'set', key: 'damping', value: kDamping });
  const shown = await dnurbs(() => document.getElementById('value-stiffness').value);
  check(Number(shown) === kStiffness, `the stiffness field shows the new value ${shown}`);
  await sleep(1500);
  const start = await page.evaluate((i) => window.dnurbs.screenOf(i, [0.5, 0.5]), hat);
  const x0 = Math.round(start.x);
  const y0 = Math.round(start.y);
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  const granted = await waitFor(page, () => window.dnurbs.drag.active && window.dnurbs.drag.id !== null,
                                null, 3000, 'the grab');
  const grab = await dnurbs(() => ({ ...window.dnurbs.drag, origin: null, plane: null }));
  check(granted && grab.model === hat, `mouse down at (${x0}, ${y0}) grabs model ${grab.model} (drag ${grab.id})`);
  check(Math.abs(grab.at[0] - 0.5) < 0.02 && Math.abs(grab.at[1] - 0.5) < 0.02,
        `the picked material point ${grab.at.map((u) => u.toFixed(4))} is the crown's (0.5, 0.5) ` +
        'to within a mesh cell\'s 0.02');
  for (let i = 1; i <= kDragMoves; i++) {
    await page.mouse.move(x0, y0 - (kDragPixels * i) / kDragMoves);
    await sleep(60);
  }
  await sleep(300);
  // The expected target, from the camera: a plane facing the camera at depth d maps one pixel to
  // 2 d tan(fov/2) / H world units along the screen's up direction
  const camera = await dnurbs(() => {
    const c = window.dnurbs.camera;
    const e = c.matrixWorld.elements;
    return { position: c.position.toArray(), forward: [-e[8], -e[9], -e[10]], up: [e[4], e[5], e[6]],
             fov: c.fov, height: window.dnurbs.renderer.domElement.clientHeight };
  });
  const p0 = grab.target;
  const depth = vec.dot(vec.sub(p0, camera.position), camera.forward);
  const worldPerPixel = (2 * depth * Math.tan((camera.fov * Math.PI) / 360)) / camera.height;
  const displacement = kDragPixels * worldPerPixel;
  const expected = vec.add(p0, vec.scale(camera.up, displacement));
  const target = await dnurbs(() => window.dnurbs.drag.target);
  const targetError = vec.norm(vec.sub(target, expected)) / displacement;
  console.log(`     grab point ${p0.map((x) => x.toFixed(5))}, depth ${depth.toFixed(4)}, ` +
              `${worldPerPixel.toExponential(4)} per pixel`);
  // Both are computed in double precision from the same camera; the error is rounding
  check(targetError < 1e-6, `the page's target ${target.map((x) => x.toFixed(5))} is the predicted ` +
        `${expected.map((x) => x.toFixed(5))}: ${kDragPixels} px = ${displacement.toFixed(5)} world, ` +
        `|difference| / displacement = ${targetError.toExponential(2)}`);

  // Hold until the crown settles: its position changes by less than 1e-6 of the displacement
  // between polls 250 ms apart, three times running
  const settleBegin = Date.now();
  let crown = null;
  let still = 0;
  let peakKinetic = 0;
  while (still < 3 && Date.now() - settleBegin < kSettleLimitMs) {
    await sleep(250);
    const now = (await request({ type: 'query', model: hat, at: [0.5, 0.5] })).position;
    peakKinetic = Math.max(peakKinetic, await dnurbs(() => window.dnurbs.status.kinetic));
    still = crown && vec.norm(vec.sub(now, crown)) < 1e-6 * displacement ? still + 1 : 0;
    crown = now;
  }
  const kinetic = await dnurbs(() => window.dnurbs.status.kinetic);
  check(still >= 3, `the crown settles in ${Date.now() - settleBegin} ms (scene kinetic energy ` +
        `${kinetic.toExponential(2)}, ${(kinetic / peakKinetic).toExponential(2)} of its peak ` +
        `${peakKinetic.toExponential(2)}; the pendulum keeps swinging)`);
  const crownMoved = vec.norm(vec.sub(crown, p0));
  const crownError = vec.norm(vec.sub(crown, target)) / displacement;
  check(crownMoved > 0.5 * displacement, `the crown moved ${crownMoved.toFixed(5)} (target ` +
        `${displacement.toFixed(5)} away)`);
  // The spring (k = 1e4) against the sheet's own stiffness: the crown stops short of the
  // target by a small fraction of the displacement
  check(crownError < 0.05, `|crown - target| / displacement = ${crownError.toExponential(3)} (< 5%)`);
  await page.mouse.up();
  const released = await waitFor(page, () => !window.dnurbs.drag.active && window.dnurbs.status.drags === 0,
                                 null, 3000, 'the release');
  check(released, 'mouse up releases the drag (status drags = 0)');

  // Save: the hat's shape file is the shape the server reports
  await request({ type: 'pause' });
  await page.click('#save');
  await waitFor(page, () => document.getElementById('message').textContent.startsWith('saved'),
                null, 5000, 'the saved reply');
  const saved = await request({ type: 'save' });
  const shapeReply = await request({ type: 'shape', model: hat });
  const file = path.join(out, 'hat.json');
  check(saved.files.some((f) => path.resolve(f) === file) && fs.existsSync(file),
        `save wrote ${saved.files.length} files: ${saved.files.map((f) => path.basename(f)).join(', ')}`);
  const messageLine = await dnurbs(() => document.getElementById('message').textContent);
  check(messageLine.includes('hat.json'), `the save button's reply lists the files: "${messageLine}"`);
  if (fs.existsSync(file)) {
    const onDisk = JSON.parse(fs.readFileSync(file, 'utf8'));
    const d = numberDifferences(onDisk, shapeReply.shape);
    check(d !== null, 'hat.json has the structure of the shape reply (same keys, sizes, strings)');
    if (d !== null) {
      for (const key of Object.keys(d).filter((k) => !k.endsWith(':scale') && k !== '')) {
        const relative = d[key] / Math.max(d[`${key}:scale`], 1e-300);
        // Both are the server's doubles printed as JSON: equal to the last digit
        check(relative <= 1e-12, `hat.json ${key}: largest difference ${d[key].toExponential(2)}, ` +
              `${relative.toExponential(2)} relative`);
      }
      if (!('weights' in d)) console.log('     (no weights in either: a non-rational shape, all weights 1)');
    }
  }

  // Pin: ctrl-click on the torus adds a pin and a sphere; reset removes both
  const torus = await dnurbs(() => window.dnurbs.scene.models.findIndex((m) => m.name === 'torus'));
  if (torus >= 0) {
    const p = await page.evaluate((i) => window.dnurbs.screenOf(i, [0.25, 0.5]), torus);
    await page.keyboard.down('Control');
    await page.mouse.click(Math.round(p.x), Math.round(p.y));
    await page.keyboard.up('Control');
    const pinned = await waitFor(page, () => window.dnurbs.status.pins === 1, null, 3000, 'the pin');
    check(pinned, 'ctrl-click on the torus pins a point (status pins = 1)');
    await request({ type: 'reset' });
    const cleared = await waitFor(page, () => window.dnurbs.status.pins === 0, null, 3000, 'the reset');
    check(cleared, 'reset removes the pin');
  }

  // Shift-drag pushes with force = 0.2 stiffness × (cursor's plane point - grab point) (the
  // page's push gain); undo (the button) puts the crown back where it was when the push began
  await request({ type: 'set', key: 'stiffness', value: 100 });
  await request({ type: 'play' });
  await sleep(1000);
  const crownBefore = (await request({ type: 'query', model: hat, at: [0.5, 0.5] })).position;
  const pushStart = await page.evaluate((i) => window.dnurbs.screenOf(i, [0.5, 0.5]), hat);
  await page.keyboard.down('Shift');
  await page.mouse.move(Math.round(pushStart.x), Math.round(pushStart.y));
  await page.mouse.down();
  await waitFor(page, () => window.dnurbs.drag.id !== null && window.dnurbs.drag.push, null, 3000, 'the push');
  await page.mouse.move(Math.round(pushStart.x), Math.round(pushStart.y) - 20);
  await sleep(800);
  const push = await dnurbs(() => ({ ...window.dnurbs.drag, origin: window.dnurbs.drag.origin.toArray(),
                                     plane: null, drags: window.dnurbs.status.drags,
                                     stiffness: window.dnurbs.settings.stiffness }));
  const expectedForce = vec.scale(vec.sub(push.target, push.origin), 0.2 * push.stiffness);
  const forceError = vec.norm(vec.sub(push.force, expectedForce)) / vec.norm(expectedForce);
  check(push.push && push.drags === 1 && forceError < 1e-12,
        `shift-drag pushes (drag ${push.id}, ${push.drags} drag on the server) with force ` +
        `${push.force.map((f) => f.toFixed(3))} = 0.2 stiffness × offset (relative difference ${forceError.toExponential(1)})`);
  const crownPushed = (await request({ type: 'query', model: hat, at: [0.5, 0.5] })).position;
  await page.mouse.up();
  await page.keyboard.up('Shift');
  await waitFor(page, () => window.dnurbs.status.drags === 0, null, 3000, 'the push\'s release');
  await request({ type: 'pause' });
  await page.click('#undo');
  await sleep(500);
  const crownUndone = (await request({ type: 'query', model: hat, at: [0.5, 0.5] })).position;
  const pushMoved = vec.norm(vec.sub(crownPushed, crownBefore));
  const undoError = vec.norm(vec.sub(crownUndone, crownBefore));
  // The hat was at rest before the push: the state undo restores has the crown where it was
  check(pushMoved > 1e-3 && undoError < 1e-3 * pushMoved,
        `the push moved the crown ${pushMoved.toExponential(3)}; after undo it is ` +
        `${undoError.toExponential(2)} from where it was`);

  // Orbit: a drag on the background turns the camera and starts no drag
  const cameraBefore = await dnurbs(() => window.dnurbs.camera.position.toArray());
  const dragsBefore = await dnurbs(() => window.dnurbs.drag.id);
  await page.mouse.move(60, 60);
  await page.mouse.down();
  await page.mouse.move(110, 70, { steps: 5 });
  await page.mouse.up();
  const cameraAfter = await dnurbs(() => window.dnurbs.camera.position.toArray());
  const dragsAfter = await dnurbs(() => window.dnurbs.drag.id);
  check(vec.norm(vec.sub(cameraAfter, cameraBefore)) > 0.1 && dragsAfter === dragsBefore,
        `a background drag orbits: the camera moved ${vec.norm(vec.sub(cameraAfter, cameraBefore)).toFixed(3)}, no drag began`);

  // The control nets checkbox shows the nets
  await page.click('#nets');
  const netsShown = await dnurbs(() => window.dnurbs.scene.models.filter((m) => m.control_net).length);
  const netsVisible = await page.evaluate(() => {
    let visible = 0;
    window.dnurbs.meshes[0].parent.traverse((o) => {
      if (o.userData.controlNet !== undefined && o.visible) visible++;
    });
    return visible;
  });
  check(netsVisible === netsShown, `the control nets checkbox shows ${netsVisible} nets of ${netsShown}`);

  // The screenshot: the view is not blank
  await request({ type: 'play' });
  await sleep(500);
  const shot = path.join(out, 'e2e.png');
  await page.screenshot({ path: shot });
  const rect = await dnurbs(() => {
    const r = window.dnurbs.renderer.domElement.getBoundingClientRect();
    return { x: Math.round(r.left), y: Math.round(r.top), w: Math.round(r.width), h: Math.round(r.height) };
  });
  const png = PNG.sync.read(fs.readFileSync(shot));
  const counts = new Map();
  for (let y = rect.y; y < rect.y + rect.h; y++) {
    for (let x = rect.x; x < rect.x + rect.w; x++) {
      const i = 4 * (y * png.width + x);
      const key = (png.data[i] << 16) | (png.data[i + 1] << 8) | png.data[i + 2];
      counts.set(key, (counts.get(key) ?? 0) + 1);
    }
  }
  const [background, backgroundCount] = [...counts.entries()].sort((a, b) => b[1] - a[1])[0];
  const differing = 1 - backgroundCount / (rect.w * rect.h);
  check(differing > 0.01, `${shot}: ${(100 * differing).toFixed(1)}% of the view's pixels differ from ` +
        `the background #${background.toString(16).padStart(6, '0')}`);
  check(counts.size > 50, `${counts.size} distinct colours in the view`);

  check(consoleErrors.length === 0, `no console errors (${consoleErrors.length})`);
  for (const text of consoleErrors) console.log(`     console error: ${text}`);
  for (const text of consoleWarnings) console.log(`     console warning: ${text}`);
  check(consoleWarnings.length === 0, `no console warnings (${consoleWarnings.length})`);
} catch (error) {
  check(false, `the test ran to its end: ${error.stack}`);
} finally {
  await browser.close();
  const stopped = await server.stop(5000);
  check(stopped.code === 0, `SIGTERM stops the server with exit code ${stopped.code} in ${stopped.ms} ms`);
}
checks.finish();
