// The 3D view of the sculpting page: one shaded mesh per model of the `scene` message, the
// control nets, pins, the drag's rubber band, a ground grid, an orbiting camera (z up), picking
// of material points and projection of material points to the screen.

import * as THREE from '/three/build/three.module.js';
import { OrbitControls } from '/three/examples/jsm/controls/OrbitControls.js';

const kBackground = 0x1d2127;
const kPalette = [0xd9a441, 0x4f9dd9, 0x8fc46a, 0xd9685a, 0xb07fd9, 0x5ac9c0];
const kNetColor = 0xf2f2f2;
const kPinColor = 0xff3355;
const kDragColor = 0xffee55;
const kViewDirection = new THREE.Vector3(0.15, -1, 0.6).normalize();  // from the target

// The smallest and largest value of each parametric coordinate over a model's vertices.
function uvRange(uv, dimension) {
  const range = [];
  for (let k = 0; k < dimension; k++) {
    let lo = Infinity;
    let hi = -Infinity;
    for (let i = k; i < uv.length; i += 2) {
      lo = Math.min(lo, uv[i]);
      hi = Math.max(hi, uv[i]);
    }
    range.push([lo, hi]);
  }
  return range;
}

export class View {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.appendChild(this.renderer.domElement);
    this.canvas = this.renderer.domElement;

    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(kBackground);
    this.camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(0, -6, 3);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => { this.dirty = true; });

    this.scene.add(new THREE.HemisphereLight(0xe8f0ff, 0x30281e, 0.55));
    const key = new THREE.DirectionalLight(0xffffff, 0.75);
    key.position.set(2, -3, 5);
    const fill = new THREE.DirectionalLight(0xffffff, 0.3);
    fill.position.set(-4, 2, 1);
    this.scene.add(key, fill);

    this.models = [];    // per model: { mesh, net, uv, dimension, range }
    this.meshes = [];
    this.pins = new THREE.Group();
    this.scene.add(this.pins);
    this.grid = null;
    this.framed = false;
    this.netsVisible = false;
    this.raycaster = new THREE.Raycaster();
    this.dirty = true;

    this.band = new THREE.Line(new THREE.BufferGeometry(),
                               new THREE.LineBasicMaterial({ color: kDragColor }));
    this.band.geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6), 3));
    this.band.visible = false;
    this.band.frustumCulled = false;
    this.scene.add(this.band);

    this.resize();
    window.addEventListener('resize', () => this.resize());
  }

  resize() {
    const width = Math.max(1, this.container.clientWidth);
    const height = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(width, height);
    this.camera.aspect = width / height;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  // Builds the meshes and nets of a `scene` message (positions arrive with the first frame).
  build(models) {
    for (const m of this.models) {
      this.scene.remove(m.mesh, m.net);
      m.mesh.geometry.dispose();
      if (m.net) m.net.geometry.dispose();
    }
    this.models = models.map((model, i) => {
      const n = model.vertex_count;
      const geometry = new THREE.BufferGeometry();
      const Index = Math.max(n, model.control_net ? model.control_net.count : 0) > 65535
        ? Uint32Array : Uint16Array;
      geometry.setIndex(new THREE.BufferAttribute(Index.from(model.triangles), 1));
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
      geometry.setAttribute('normal', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
      // Phong, not physically based: a third of the fragment work, which software renderers
      // (and small GPUs) feel at 60 frames a second
      const material = new THREE.MeshPhongMaterial({
        color: kPalette[i % kPalette.length], shininess: 30, specular: 0x222222,
        side: THREE.DoubleSide,
        // pushed back a little in depth so that a control net lying on the surface shows
        polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
      const mesh = new THREE.Mesh(geometry, material);
      mesh.name = model.name;
      mesh.userData.model = model.index;
      this.scene.add(mesh);
      let net = null;
      if (model.control_net) {
        const netGeometry = new THREE.BufferGeometry();
        netGeometry.setAttribute(
          'position', new THREE.BufferAttribute(new Float32Array(3 * model.control_net.count), 3));
        netGeometry.setIndex(new THREE.BufferAttribute(Index.from(model.control_net.lines), 1));
        net = new THREE.LineSegments(
          netGeometry, new THREE.LineBasicMaterial({ color: kNetColor, transparent: true, opacity: 0.7 }));
        net.frustumCulled = false;
        net.userData.controlNet = model.index;
        net.visible = this.netsVisible;
        this.scene.add(net);
      }
      const dimension = model.kind === 'curve' ? 1 : 2;
      return { mesh, net, uv: model.uv, dimension, range: uvRange(model.uv, dimension),
               seen: false };
    });
    this.meshes = this.models.map((m) => m.mesh);
    this.framed = false;
    this.clearPins();
    this.dirty = true;
  }

  // Copies a parsed frame's positions, normals and control points into the geometries.
  applyFrame(frame) {
    for (const f of frame.models) {
      const m = this.models[f.index];
      if (!m) continue;
      const geometry = m.mesh.geometry;
      const position = geometry.getAttribute('position');
      if (f.positions.length !== position.array.length) continue;
      position.array.set(f.positions);
      position.needsUpdate = true;
      const normal = geometry.getAttribute('normal');
      normal.array.set(f.normals);
      normal.needsUpdate = true;
      geometry.computeBoundingSphere();
      m.seen = true;
      if (m.net) {
        const points = m.net.geometry.getAttribute('position');
        if (f.controls.length === points.array.length) {
          points.array.set(f.controls);
          points.needsUpdate = true;
        }
      }
    }
    if (!this.framed && this.models.length > 0 && this.models.every((m) => m.seen)) {
      this.frameCamera();
    }
    this.dirty = true;
  }

  // Points the camera at the bounding box of every shape, from the front and above, and lays
  // the ground grid under it.
  frameCamera() {
    const box = new THREE.Box3();
    for (const m of this.models) {
      m.mesh.geometry.computeBoundingBox();
      box.union(m.mesh.geometry.boundingBox);
    }
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-3);
    // The camera looks along -kViewDirection with z up; the distance D puts every vertex c
    // (relative to the box's center) inside the frustum: |c·right| <= tan(fovX/2) (D + c·forward),
    // and so for up; then a 5% margin.
    const forward = kViewDirection.clone().negate();
    const right = new THREE.Vector3().crossVectors(forward, this.camera.up).normalize();
    const up = new THREE.Vector3().crossVectors(right, forward);
    const tanY = Math.tan(((this.camera.fov / 2) * Math.PI) / 180);
    const tanX = tanY * this.camera.aspect;
    let distance = 1e-3;
    const c = new THREE.Vector3();
    for (const m of this.models) {
      const position = m.mesh.geometry.getAttribute('position');
      for (let i = 0; i < position.count; i++) {
        c.fromBufferAttribute(position, i).sub(center);
        distance = Math.max(distance, Math.abs(c.dot(right)) / tanX - c.dot(forward),
                            Math.abs(c.dot(up)) / tanY - c.dot(forward));
      }
    }
    distance *= 1.05;
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.position.copy(center).addScaledVector(kViewDirection, distance);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(center);
    this.controls.update();

    if (this.grid) this.scene.remove(this.grid);
    const extent = Math.max(box.max.x - box.min.x, box.max.y - box.min.y);
    const step = 10 ** Math.floor(Math.log10(Math.max(extent, 1e-3) / 4));
    const divisions = Math.min(200, 2 * Math.ceil(extent / step));
    this.grid = new THREE.GridHelper(divisions * step, divisions, 0x59606b, 0x383d45);
    this.grid.rotation.x = Math.PI / 2;  // GridHelper lies in xz; the scene's ground is xy
    this.grid.position.set(center.x, center.y, box.min.z - 0.02 * radius);
    this.scene.add(this.grid);
    this.framed = true;
    this.dirty = true;
  }

  setNetsVisible(visible) {
    this.netsVisible = visible;
    for (const m of this.models) if (m.net) m.net.visible = visible;
    this.dirty = true;
  }

  // Normalized device coordinates of a client pixel.
  ndc(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    return new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1,
                             -((clientY - rect.top) / rect.height) * 2 + 1);
  }

  // The shape under a client pixel: { model, at, point, triangle: [a, b, c], weights }, or null.
  // `at` interpolates the triangle's vertices' material points with the hit's barycentric
  // coordinates; across a periodic seam (a triangle whose parameters span over half the
  // model's range) it takes the nearest vertex's material point instead.
  pick(clientX, clientY) {
    this.raycaster.setFromCamera(this.ndc(clientX, clientY), this.camera);
    const hit = this.raycaster.intersectObjects(this.meshes, false)[0];
    if (!hit || !hit.face) return null;
    const m = this.models[this.meshes.indexOf(hit.object)];
    const position = hit.object.geometry.getAttribute('position');
    const triangle = [hit.face.a, hit.face.b, hit.face.c];
    const corners = triangle.map((i) => new THREE.Vector3().fromBufferAttribute(position, i));
    const w = THREE.Triangle.getBarycoord(hit.point, ...corners, new THREE.Vector3()).toArray();
    const nearest = triangle[w.indexOf(Math.max(...w))];
    const at = [];
    for (let k = 0; k < m.dimension; k++) {
      const values = triangle.map((i) => m.uv[2 * i + k]);
      const [lo, hi] = m.range[k];
      const seam = Math.max(...values) - Math.min(...values) > 0.5 * (hi - lo);
      const value = seam ? m.uv[2 * nearest + k]
                         : values[0] * w[0] + values[1] * w[1] + values[2] * w[2];
      at.push(Math.min(hi, Math.max(lo, value)));
    }
    return { model: hit.object.userData.model, at, point: hit.point.clone(), triangle, weights: w };
  }

  // Where the cursor's ray meets `plane`, or null when they are parallel.
  planePoint(clientX, clientY, plane) {
    this.raycaster.setFromCamera(this.ndc(clientX, clientY), this.camera);
    return this.raycaster.ray.intersectPlane(plane, new THREE.Vector3());
  }

  // The plane through `point` facing the camera.
  facingPlane(point) {
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    return new THREE.Plane().setFromNormalAndCoplanarPoint(normal, point);
  }

  // The current position of a material point given as a triangle and barycentric weights.
  surfacePoint(model, triangle, weights) {
    const position = this.models[model].mesh.geometry.getAttribute('position');
    const p = new THREE.Vector3();
    const v = new THREE.Vector3();
    triangle.forEach((i, k) => p.addScaledVector(v.fromBufferAttribute(position, i), weights[k]));
    return p;
  }

  // Client pixels of x(at) of a model, from the current mesh vertex nearest `at` in the
  // parameters.
  screenOf(model, at) {
    const m = this.models[model];
    if (!m) throw new Error(`no model ${model}`);
    let best = 0;
    let bestDistance = Infinity;
    for (let i = 0; 2 * i < m.uv.length; i++) {
      let d = 0;
      for (let k = 0; k < m.dimension; k++) d += (m.uv[2 * i + k] - at[k]) ** 2;
      if (d < bestDistance) {
        bestDistance = d;
        best = i;
      }
    }
    const p = new THREE.Vector3().fromBufferAttribute(m.mesh.geometry.getAttribute('position'), best);
    p.project(this.camera);
    const rect = this.canvas.getBoundingClientRect();
    return { x: rect.left + ((p.x + 1) / 2) * rect.width,
             y: rect.top + ((1 - p.y) / 2) * rect.height };
  }

  addPin(position) {
    const size = this.framed ? this.camera.position.distanceTo(this.controls.target) / 120 : 0.02;
    const sphere = new THREE.Mesh(new THREE.SphereBufferGeometry(size, 12, 8),
                                  new THREE.MeshStandardMaterial({ color: kPinColor }));
    sphere.position.fromArray(position);
    this.pins.add(sphere);
    this.dirty = true;
  }

  clearPins() {
    for (const pin of [...this.pins.children]) {
      pin.geometry.dispose();
      this.pins.remove(pin);
    }
    this.dirty = true;
  }

  // The drag's rubber band from the grabbed material point to the target (null hides it).
  showBand(from, to) {
    this.band.visible = Boolean(from && to);
    if (this.band.visible) {
      const position = this.band.geometry.getAttribute('position');
      position.array.set([from.x, from.y, from.z, to.x, to.y, to.z]);
      position.needsUpdate = true;
    }
    this.dirty = true;
  }

  // Dynamic resolution: when frames arrive faster than the page draws them (a software
  // renderer, a small GPU), draw fewer pixels, down to half the device's, so that the view keeps
  // 30 frames a second or more; draw more again when there is room.
  adaptResolution(drawn, received) {
    const device = window.devicePixelRatio || 1;
    const ratio = this.renderer.getPixelRatio();
    let next = ratio;
    if (drawn < Math.min(30, received - 2)) next = Math.max(0.5 * device, ratio * 0.85);
    else if (drawn >= Math.min(55, received - 1)) next = Math.min(device, ratio * 1.1);
    if (next !== ratio) {
      this.renderer.setPixelRatio(next);  // r111: resizes the drawing buffer, not the canvas
      this.dirty = true;
    }
  }

  render() {
    this.renderer.render(this.scene, this.camera);
    this.dirty = false;
  }
}
