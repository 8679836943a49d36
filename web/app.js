// dnurbs serve's sculpting page (docs/serve.md): connects to /ws, shows the scene's shapes,
// turns mouse gestures into grab / push / pin requests and wires the controls panel. The
// browser tests read and drive it through window.dnurbs.

import * as THREE from '/three/build/three.module.js';
import { Connection } from '/connection.js';
import { Panel } from '/panel.js';
import { View } from '/view.js';

const view = new View(document.getElementById('view'));

// A rate measured over the last second: call tick() per event, read value.
class Rate {
  constructor() {
    this.times = [];
  }

  tick(now = performance.now()) {
    this.times.push(now);
    while (this.times[0] < now - 1000) this.times.shift();
  }

  get value() {
    const now = performance.now();
    while (this.times.length && this.times[0] < now - 1000) this.times.shift();
    return this.times.length;
  }
}
const renderRate = new Rate();
const frameRate = new Rate();

// The drag in progress (and, after it ends, the last one): the material point `at` of model
// `model`, the spring's `target` (or the push's `force`), the server's drag id once granted.
const drag = {
  active: false, id: null, target: null, at: null, model: null, push: false, force: null,
  origin: null, plane: null, triangle: null, weights: null, dirty: false,
};

const hooks = {
  connected: false,
  scene: null,
  status: null,
  settings: null,
  framesReceived: 0,
  renderFps: 0,
  receivedFps: 0,
  camera: view.camera,
  renderer: view.renderer,
  meshes: view.meshes,
  drag,
  errors: [],
  request: (message) => connection.request(message),
  sendRaw: (text) => connection.sendRaw(text),
  screenOf: (model, at) => view.screenOf(model, at),
};
window.dnurbs = hooks;

const panel = new Panel(document.getElementById('panel'), {
  command(type) {
    connection.request({ type }).then(() => {
      if (type === 'reset') view.clearPins();
    }, showError);
  },
  set(key, value) {
    connection.request({ type: 'set', key, value }).then(
      () => panel.message(`${key} = ${value}`), showError);
  },
  nets(visible) { view.setNetsVisible(visible); },
});

function showError(error) {
  panel.message(error.message || String(error), true);
}

function onMessage(message) {
  switch (message.type) {
    case 'scene':
      hooks.scene = message;
      hooks.settings = message.settings;
      view.build(message.models);
      hooks.meshes = view.meshes;
      panel.showSettings(message.settings);
      const names = message.models.map((m) => m.name).join(', ');
      panel.message(`${message.models.length} model${message.models.length === 1 ? '' : 's'}: ${names}`);
      break;
    case 'status':
      hooks.status = message;
      hooks.settings = message.settings;
      panel.showSettings(message.settings);
      panel.addSample(message);
      if (message.pins === 0 && view.pins.children.length > 0) view.clearPins();
      break;
    case 'saved':
      panel.message(`saved ${message.files.join(', ')}`);
      break;
    case 'error':
      hooks.errors.push(message);
      panel.message(`error${message.request ? ` (${message.request})` : ''}: ${message.message}`, true);
      break;
    default:
      break;
  }
}

const connection = new Connection(`ws://${location.host}/ws`, {
  open() {
    hooks.connected = true;
    panel.message('connected');
  },
  close(event) {
    hooks.connected = false;
    drag.active = false;
    panel.message(`disconnected from the server (${event.code}); reload the page to reconnect`, true);
  },
  message: onMessage,
  frame(frame) {
    hooks.framesReceived++;
    frameRate.tick();
    view.applyFrame(frame);
  },
  error(text) {
    hooks.errors.push({ type: 'error', message: text, request: '' });
    panel.message(text, true);
  },
});

// Gestures: a left press on a shape grabs (shift: pushes, ctrl or alt: pins); on the
// background it is the camera's (OrbitControls listens to mousedown, which follows
// pointerdown, so disabling it here keeps the camera still during a drag).
const canvas = view.canvas;

// A push's force per unit of the cursor's offset from the grabbed point: a fifth of the spring
// stiffness (20 at the default stiffness 100), so that a push moves a shape about as far as a
// pull of the same offset on the demo's sheet, not hundreds of times farther.
const kPushGainPerStiffness = 0.2;

function pushGain() {
  return kPushGainPerStiffness * (hooks.settings ? hooks.settings.stiffness : 100);
}

canvas.addEventListener('pointerdown', (event) => {
  if (event.button !== 0 || !hooks.connected || drag.active) return;
  const hit = view.pick(event.clientX, event.clientY);
  if (!hit) return;
  view.controls.enabled = false;
  if (event.ctrlKey || event.altKey || event.metaKey) {
    connection.request({ type: 'pin', model: hit.model, at: hit.at }).then((reply) => {
      view.addPin(reply.position || hit.point.toArray());
      panel.message(`pinned ${hooks.scene.models[hit.model].name} at (${hit.at.map((x) => x.toFixed(3)).join(', ')})`);
    }, showError);
    return;
  }
  canvas.setPointerCapture(event.pointerId);
  Object.assign(drag, {
    active: true, id: null, model: hit.model, at: hit.at, push: event.shiftKey,
    origin: hit.point, target: hit.point.toArray(), force: event.shiftKey ? [0, 0, 0] : null,
    plane: view.facingPlane(hit.point), triangle: hit.triangle, weights: hit.weights,
    dirty: false,
  });
  const message = drag.push
    ? { type: 'push', model: hit.model, at: hit.at, force: drag.force }
    : { type: 'grab', model: hit.model, at: hit.at, target: drag.target };
  const started = drag;
  connection.request(message).then((reply) => {
    started.id = reply.drag;
    // Released before the server granted the drag: release it now
    if (!started.active) connection.request({ type: 'release', drag: reply.drag }).catch(showError);
  }, (error) => {
    started.active = false;
    view.showBand(null, null);
    showError(error);
  });
});

canvas.addEventListener('pointermove', (event) => {
  if (!drag.active) return;
  const point = view.planePoint(event.clientX, event.clientY, drag.plane);
  if (!point) return;
  drag.target = point.toArray();
  if (drag.push) drag.force = point.clone().sub(drag.origin).multiplyScalar(pushGain()).toArray();
  drag.dirty = true;
});

function endDrag(event) {
  if (event.button !== 0) return;
  view.controls.enabled = true;
  if (!drag.active) return;
  drag.active = false;
  if (canvas.hasPointerCapture(event.pointerId)) canvas.releasePointerCapture(event.pointerId);
  view.showBand(null, null);
  if (drag.id !== null) {
    const id = drag.id;
    connection.request({ type: 'release', drag: id }).catch(showError);
  }
}
window.addEventListener('pointerup', endDrag);
window.addEventListener('pointercancel', endDrag);

// One `move` per animation frame at most, with the latest target or force.
function flushMove() {
  if (!drag.active || drag.id === null || !drag.dirty) return;
  drag.dirty = false;
  const message = drag.push ? { type: 'move', drag: drag.id, force: drag.force }
                            : { type: 'move', drag: drag.id, target: drag.target };
  connection.send(message);
}

function loop() {
  flushMove();
  if (drag.active) {
    view.showBand(view.surfacePoint(drag.model, drag.triangle, drag.weights),
                  new THREE.Vector3().fromArray(drag.target));
  }
  if (view.dirty) {
    view.render();
    renderRate.tick();
  }
  requestAnimationFrame(loop);
}
requestAnimationFrame(loop);

setInterval(() => view.adaptResolution(renderRate.value, frameRate.value), 1000);

setInterval(() => {
  hooks.renderFps = renderRate.value;
  hooks.receivedFps = frameRate.value;
  panel.showStatus(hooks.status, { render: hooks.renderFps, received: hooks.receivedFps });
}, 250);
