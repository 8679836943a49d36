// The controls panel of the sculpting page: buttons, the settings' sliders (logarithmic), the
// status line, the divergence banner, the message line and the live energy plot.

const kSliderSteps = 1000;
const kPlotSamples = 300;

// The settings of docs/serve.md with the slider ranges (log scale from `lo` to `hi`; `zero`:
// the slider's leftmost position is 0, which the setting allows).
export const kSettings = [
  { key: 'stiffness', lo: 1e-2, hi: 1e6, zero: false,
    tip: 'mouse spring stiffness k (force per unit length). A shift-drag push applies ' +
         '0.2 k × the cursor\'s offset from the grabbed point (the push gain).' },
  { key: 'tension', lo: 1e-3, hi: 1e4, zero: true,
    tip: 'membrane tension (surfaces: a10 = a01; curves: tension)' },
  { key: 'rigidity', lo: 1e-3, hi: 1e4, zero: true,
    tip: 'bending rigidity (surfaces: b20 = b11 = b02, the thin plate; curves: rigidity)' },
  { key: 'density', lo: 1e-3, hi: 1e4, zero: false, tip: 'mass density' },
  { key: 'damping', lo: 1e-3, hi: 1e4, zero: true, tip: 'damping density' },
  { key: 'dt', lo: 1e-4, hi: 0.1, zero: false, tip: 'time step of the simulation' },
];

function toSlider(spec, value) {
  if (spec.zero && value <= 0) return 0;
  const first = spec.zero ? 1 : 0;
  const t = (Math.log10(Math.max(value, spec.lo)) - Math.log10(spec.lo)) /
            (Math.log10(spec.hi) - Math.log10(spec.lo));
  return Math.round(first + Math.min(1, Math.max(0, t)) * (kSliderSteps - first));
}

function fromSlider(spec, position) {
  if (spec.zero && position === 0) return 0;
  const first = spec.zero ? 1 : 0;
  const t = (position - first) / (kSliderSteps - first);
  const value = 10 ** (Math.log10(spec.lo) + t * (Math.log10(spec.hi) - Math.log10(spec.lo)));
  return Number(value.toPrecision(3));
}

const format = (x, digits = 3) => (Number.isFinite(x) ? Number(x.toPrecision(digits)).toString() : '–');

export class Panel {
  // actions: { command(type), set(key, value), nets(visible) }
  constructor(root, actions) {
    this.root = root;
    this.actions = actions;
    this.samples = [];
    this.editing = new Set();
    for (const type of ['play', 'pause', 'step', 'reset', 'undo', 'save']) {
      root.querySelector(`#${type}`).addEventListener('click', () => actions.command(type));
    }
    root.querySelector('#nets').addEventListener('change', (e) => actions.nets(e.target.checked));
    const sliders = root.querySelector('#sliders');
    this.inputs = {};
    for (const spec of kSettings) this.inputs[spec.key] = this.addSlider(sliders, spec);
    this.statusLine = root.querySelector('#status');
    this.banner = root.querySelector('#diverged');
    this.messageLine = root.querySelector('#message');
    this.plot = root.querySelector('#energy');
  }

  addSlider(parent, spec) {
    const row = document.createElement('label');
    row.className = 'slider';
    row.title = spec.tip;
    const name = document.createElement('span');
    name.textContent = spec.key;
    const range = document.createElement('input');
    Object.assign(range, { type: 'range', min: 0, max: kSliderSteps, step: 1, id: `set-${spec.key}` });
    const number = document.createElement('input');
    Object.assign(number, { type: 'number', step: 'any', id: `value-${spec.key}` });
    row.append(name, range, number);
    parent.append(row);
    const begin = () => this.editing.add(spec.key);
    const end = () => this.editing.delete(spec.key);
    range.addEventListener('pointerdown', begin);
    range.addEventListener('input', () => {
      begin();
      number.value = fromSlider(spec, Number(range.value));
    });
    range.addEventListener('change', () => {
      end();
      this.actions.set(spec.key, fromSlider(spec, Number(range.value)));
    });
    number.addEventListener('focus', begin);
    number.addEventListener('blur', end);
    number.addEventListener('change', () => {
      const value = Number(number.value);
      range.value = toSlider(spec, value);
      this.actions.set(spec.key, value);
    });
    return { spec, range, number };
  }

  // Shows the server's settings, except on the control the user is moving.
  showSettings(settings) {
    if (!settings) return;
    for (const { spec, range, number } of Object.values(this.inputs)) {
      const value = settings[spec.key];
      if (typeof value !== 'number' || this.editing.has(spec.key)) continue;
      range.value = toSlider(spec, value);
      number.value = format(value, 6);
    }
  }

  // rates: { render, received } measured on the page, per second.
  showStatus(status, rates) {
    const s = status || {};
    const parts = [
      `render ${format(rates.render)} fps`,
      `received ${format(rates.received)} frames/s`,
      `step ${format(s.step_ms, 2)} ms`,
      `${format(s.steps_per_second)} steps/s`,
      `t = ${format(s.time, 4)}`,
      `step ${s.step ?? '–'}`,
      `${s.clients ?? '–'} client${s.clients === 1 ? '' : 's'}`,
      `${s.drags ?? 0} drag${s.drags === 1 ? '' : 's'}, ${s.pins ?? 0} pin${s.pins === 1 ? '' : 's'}`,
      s.playing ? 'playing' : 'paused',
    ];
    this.statusLine.textContent = parts.join(' · ');
    this.root.querySelector('#play').classList.toggle('active', Boolean(s.playing));
    this.root.querySelector('#pause').classList.toggle('active', s.playing === false);
    this.banner.textContent = s.diverged ? `diverged: ${s.diverged}` : '';
    this.banner.hidden = !s.diverged;
  }

  message(text, isError = false) {
    this.messageLine.textContent = text;
    this.messageLine.classList.toggle('error', isError);
  }

  addSample(status) {
    this.samples.push([status.kinetic, status.potential + status.spring, status.energy]);
    if (this.samples.length > kPlotSamples) this.samples.shift();
    this.drawPlot();
  }

  // The last samples of the kinetic, potential + spring and total energy, each scaled to the
  // common range of the three.
  drawPlot() {
    const canvas = this.plot;
    const width = canvas.clientWidth || canvas.width;
    const height = canvas.clientHeight || canvas.height;
    const ratio = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(width * ratio)) canvas.width = Math.round(width * ratio);
    if (canvas.height !== Math.round(height * ratio)) canvas.height = Math.round(height * ratio);
    const g = canvas.getContext('2d');
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, width, height);
    const values = this.samples.flat().filter(Number.isFinite);
    if (values.length === 0) return;
    let lo = Math.min(0, ...values);
    let hi = Math.max(...values);
    if (hi - lo < 1e-12) hi = lo + 1;
    const pad = 4;
    const x = (i) => pad + (i / (kPlotSamples - 1)) * (width - 2 * pad);
    const y = (v) => height - pad - ((v - lo) / (hi - lo)) * (height - 2 * pad - 12);
    const colors = ['#5ac9c0', '#d9a441', '#f2f2f2'];
    const names = ['kinetic', 'potential + spring', 'total'];
    for (let k = 0; k < 3; k++) {
      g.strokeStyle = colors[k];
      g.lineWidth = 1.5;
      g.beginPath();
      this.samples.forEach((s, i) => {
        if (i === 0) g.moveTo(x(i), y(s[k]));
        else g.lineTo(x(i), y(s[k]));
      });
      g.stroke();
    }
    g.font = '10px sans-serif';
    let left = pad;
    for (let k = 0; k < 3; k++) {
      g.fillStyle = colors[k];
      g.fillText(names[k], left, 10);
      left += g.measureText(names[k]).width + 10;
    }
    g.fillStyle = '#9aa3ad';
    g.fillText(format(hi), width - 44, 10);
  }
}
