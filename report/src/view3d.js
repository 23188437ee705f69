// 3-D deformed-shape view (three.js): the mesh stored once, node displacements per frame (or a
// mode shape), a time slider, a displacement scale factor and contour colours of a nodal or
// element result in 9 bands (ANSYS-like).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { el, f32, fmt } from './util.js';

const BANDS = ['#0000ff', '#0080ff', '#00ffff', '#00ff80', '#00ff00', '#80ff00', '#ffff00', '#ff8000', '#ff0000'];
const BAND_RGB = BANDS.map((h) => new THREE.Color(h));
const NO_VALUE = new THREE.Color('#b9bec6');
const NO_VALUE_LINE = new THREE.Color('#5a606b');
const UNIFORM = new THREE.Color('#8fb3d9');
const MODE_STEPS = 48;

/** Length of a displacement whose absent components (NaN: a 2-D model has no UZ) count as 0;
 *  NaN when all three are absent. */
function magnitude(x, y, z) {
  if (Number.isNaN(x) && Number.isNaN(y) && Number.isNaN(z)) return NaN;
  return Math.hypot(x || 0, y || 0, z || 0);
}

/** 1, 2, 5 x 10^k closest below v. */
function niceBelow(v) {
  const mag = Math.pow(10, Math.floor(Math.log10(v)));
  const m = v / mag;
  return (m >= 5 ? 5 : m >= 2 ? 2 : 1) * mag;
}

export class View3D {
  constructor(parent, data, onTime) {
    this.data = data;
    this.onTime = onTime;
    const mesh = data.mesh;
    this.xyz = f32(mesh.xyz);
    this.nNodes = mesh.node_ids.length;
    this.nElements = mesh.element_ids.length;
    this.frames = data.frames;
    this.times = data.frames.times || [];
    this.U = f32(data.frames.U);
    this.fields = (data.frames.fields || []).map((f) => ({ name: f.name, values: f32(f.values) }));
    this.modes = data.modes && data.modes.n_shapes ? f32(data.modes.shapes) : null;
    this.freqs = (data.modes && data.modes.frequencies) || [];
    this.stats = { webgl: false, triangles: 0, lines: 0, points: 0, coveredPixels: 0, renders: 0 };

    this.sets = [];
    if (this.times.length) this.sets.push({ kind: 'frames', label: `Time history (${this.times.length} frames)` });
    if (this.modes) for (let m = 0; m < data.modes.n_shapes; m++) this.sets.push({ kind: 'mode', mode: m, label: `Mode ${m + 1}: ${fmt(this.freqs[m], 5)} Hz` });
    this.set = this.sets[0] || null;
    this.step = 0;
    this.size = this.modelSize();

    this.buildDom(parent);
    if (!this.set) {
      this.viewport.appendChild(el('p', { class: 'note' }, 'No displacements are stored in this file.'));
      return;
    }
    try {
      this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      this.viewport.appendChild(el('p', { class: 'note' }, `The 3-D view needs WebGL, which this browser does not provide (${e.message}).`));
      return;
    }
    this.stats.webgl = true;
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xffffff, 1);
    this.buildScene();
    this.selectSet(0);
    new ResizeObserver(() => this.resize()).observe(this.viewport);
    this.resize();
  }

  /** Node indices that set the view's extent: those of the structure (contact and target
   *  elements aside: a rigid floor far larger than the model must not shrink it). */
  framedNodes() {
    const framed = this.data.mesh.framed_nodes;
    if (framed && framed.length) return framed;
    return Array.from({ length: this.nNodes }, (_, i) => i);
  }

  modelSize() {
    const b = new THREE.Box3();
    const v = new THREE.Vector3();
    this.framed = this.framedNodes();
    for (const i of this.framed) b.expandByPoint(v.fromArray(this.xyz, 3 * i));
    this.box = b;
    const s = b.getSize(new THREE.Vector3());
    // A model in the XY plane that moves in its plane is seen face on, Y up (a 2-D model).
    let inPlane = 0, outOfPlane = 0;
    for (const a of [this.U, this.modes || []])
      for (let i = 0; i < a.length; i += 3) {
        if (Number.isFinite(a[i])) inPlane = Math.max(inPlane, Math.abs(a[i]));
        if (Number.isFinite(a[i + 1])) inPlane = Math.max(inPlane, Math.abs(a[i + 1]));
        if (Number.isFinite(a[i + 2])) outOfPlane = Math.max(outOfPlane, Math.abs(a[i + 2]));
      }
    this.planarZ = s.z <= 1e-9 * Math.max(s.x, s.y, 1e-30) && outOfPlane <= 0.1 * inPlane;
    return Math.max(s.length(), 1e-12);
  }

  buildDom(parent) {
    this.canvas = el('canvas', { class: 'view-canvas' });
    this.legend = el('div', { class: 'contour-legend' });
    this.triad = el('div', { class: 'triad-note' });
    this.viewport = el('div', { class: 'viewport' }, this.canvas, this.legend);
    this.setSelect = el('select', { 'aria-label': 'result set', onchange: () => this.selectSet(+this.setSelect.value) }, this.sets.map((s, i) => el('option', { value: i }, s.label)));
    this.colourSelect = el('select', { 'aria-label': 'colour by', onchange: () => this.update() });
    this.slider = el('input', { type: 'range', min: 0, max: 0, value: 0, step: 1, 'aria-label': 'time', oninput: () => this.show(+this.slider.value) });
    this.playButton = el('button', { type: 'button', class: 'btn', onclick: () => this.togglePlay() }, 'Play');
    this.scaleInput = el('input', { type: 'number', min: 0, step: 'any', value: 1, class: 'scale', 'aria-label': 'displacement scale', oninput: () => this.update(true) });
    this.undeformed = el('input', { type: 'checkbox', checked: true, onchange: () => this.update() });
    this.edgesBox = el('input', { type: 'checkbox', checked: true, onchange: () => this.update() });
    this.frameRange = el('input', { type: 'checkbox', onchange: () => this.update() });
    this.timeLabel = el('span', { class: 'time-label' });
    const views = [
      ['Iso', [-5, 10, 3]],
      ['+X', [1, 0, 0]],
      ['+Y', [0, 1, 0]],
      ['+Z', [0, 0, 1]],
    ].map(([name, dir]) => el('button', { type: 'button', class: 'btn small', onclick: () => this.fit(dir) }, name));
    const controls = el(
      'div',
      { class: 'view-controls' },
      el('div', { class: 'ctl-row' }, el('label', null, 'Result ', this.setSelect), el('label', null, 'Colour by ', this.colourSelect), el('label', null, 'Displacement scale ', this.scaleInput)),
      el('div', { class: 'ctl-row' }, this.playButton, this.slider, this.timeLabel),
      el(
        'div',
        { class: 'ctl-row small' },
        el('label', null, this.undeformed, ' undeformed shape'),
        el('label', null, this.edgesBox, ' element edges'),
        el('label', null, this.frameRange, ' colour range of this frame only'),
        el('span', { class: 'views' }, 'View: ', views),
      ),
    );
    this.caption = el('figcaption');
    parent.appendChild(el('figure', { class: 'figure wide view3d' }, controls, this.viewport, this.caption));
  }

  buildScene() {
    const m = this.data.mesh;
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(30, 1, this.size * 1e-3, this.size * 100);
    this.camera.up.set(0, this.planarZ ? 1 : 0, this.planarZ ? 0 : 1);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.render());
    this.scene.add(new THREE.AmbientLight(0xffffff, 1.6));
    this.headlight = new THREE.DirectionalLight(0xffffff, 1.6);
    this.camera.add(this.headlight);
    this.scene.add(this.camera);

    const geometry = (count, perItem) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(count * perItem * 3), 3));
      g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(count * perItem * 3), 3));
      return g;
    };
    this.tri = m.triangles;
    this.triMesh = new THREE.Mesh(geometry(this.tri.length / 3, 3), new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }));
    this.lineObj = new THREE.LineSegments(geometry(m.lines.length / 2, 2), new THREE.LineBasicMaterial({ vertexColors: true }));
    this.pointObj = new THREE.Points(geometry(m.points.length, 1), new THREE.PointsMaterial({ vertexColors: true, size: 7, sizeAttenuation: false }));
    const edgeGeom = new THREE.BufferGeometry();
    edgeGeom.setAttribute('position', new THREE.BufferAttribute(new Float32Array(m.edges.length * 3), 3));
    this.edgeObj = new THREE.LineSegments(edgeGeom, new THREE.LineBasicMaterial({ color: 0x1a1a1a, transparent: true, opacity: 0.55 }));
    const undGeom = new THREE.BufferGeometry();
    const und = new Float32Array((m.edges.length + m.lines.length) * 3);
    [...m.edges, ...m.lines].forEach((n, k) => und.set(this.xyz.subarray(3 * n, 3 * n + 3), 3 * k));
    undGeom.setAttribute('position', new THREE.BufferAttribute(und, 3));
    this.undObj = new THREE.LineSegments(undGeom, new THREE.LineBasicMaterial({ color: 0x7a7a7a, transparent: true, opacity: 0.35 }));
    // A model of lines only (spars, springs) gets node markers: 1-pixel lines alone are faint.
    const used = new Set([...m.lines, ...m.points]);
    this.markerNodes = m.triangles.length ? [] : [...used];
    const markerGeom = new THREE.BufferGeometry();
    markerGeom.setAttribute('position', new THREE.BufferAttribute(new Float32Array(this.markerNodes.length * 3), 3));
    this.markerObj = new THREE.Points(markerGeom, new THREE.PointsMaterial({ color: 0x1a1a1a, size: 5, sizeAttenuation: false }));
    this.buildOverlay();
    for (const o of [this.triMesh, this.lineObj, this.pointObj, this.edgeObj, this.undObj, this.markerObj, this.overlayObj]) {
      o.frustumCulled = false;
      this.scene.add(o);
    }
    this.buildTriad();
  }

  /** Target facets (rigid floors, deformable targets): see-through, uncoloured, drawn after the
   *  structure without writing depth so they never hide it, and clipped to the structure's box
   *  grown by a quarter of its size on each side. */
  buildOverlay() {
    const tri = this.data.mesh.overlay_triangles || [];
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(tri.length * 3), 3));
    const margin = 0.25 * this.size;
    const lo = this.box.min.clone().subScalar(margin), hi = this.box.max.clone().addScalar(margin);
    const planes = [
      new THREE.Plane(new THREE.Vector3(1, 0, 0), -lo.x),
      new THREE.Plane(new THREE.Vector3(-1, 0, 0), hi.x),
      new THREE.Plane(new THREE.Vector3(0, 1, 0), -lo.y),
      new THREE.Plane(new THREE.Vector3(0, -1, 0), hi.y),
      new THREE.Plane(new THREE.Vector3(0, 0, 1), -lo.z),
      new THREE.Plane(new THREE.Vector3(0, 0, -1), hi.z),
    ];
    const material = new THREE.MeshBasicMaterial({ color: 0x9aa3ad, transparent: true, opacity: 0.25, depthWrite: false, side: THREE.DoubleSide, clippingPlanes: planes });
    this.overlayObj = new THREE.Mesh(g, material);
    this.overlayObj.renderOrder = 1;
    this.overlayTri = tri;
    if (this.renderer) this.renderer.localClippingEnabled = true;
  }

  buildTriad() {
    this.triadScene = new THREE.Scene();
    this.triadCamera = new THREE.OrthographicCamera(-1.6, 1.6, 1.6, -1.6, 0.1, 10);
    this.triadScene.add(new THREE.AxesHelper(1));
    ['X', 'Y', 'Z'].forEach((name, i) => {
      const c = document.createElement('canvas');
      c.width = c.height = 64;
      const ctx = c.getContext('2d');
      ctx.font = 'bold 44px system-ui, sans-serif';
      ctx.fillStyle = ['#c62828', '#2e7d32', '#1565c0'][i];
      ctx.textAlign = 'center';
      ctx.textBaseline = 'middle';
      ctx.fillText(name, 32, 34);
      const texture = new THREE.CanvasTexture(c);
      texture.colorSpace = THREE.SRGBColorSpace;
      const sprite = new THREE.Sprite(new THREE.SpriteMaterial({ map: texture }));
      sprite.position.set(i === 0 ? 1.3 : 0, i === 1 ? 1.3 : 0, i === 2 ? 1.3 : 0);
      sprite.scale.set(0.55, 0.55, 1);
      this.triadScene.add(sprite);
    });
  }

  /** Options of "Colour by" for the current result set. */
  colourOptions() {
    if (this.set.kind === 'mode') return ['|φ| (mode shape)', 'none'];
    return ['|U|', 'UX', 'UY', 'UZ', ...this.fields.map((f) => f.name), 'none'];
  }

  selectSet(i) {
    this.set = this.sets[i];
    this.stopPlay();
    const options = this.colourOptions();
    const previous = this.colourSelect.value;
    this.colourSelect.replaceChildren(...options.map((o) => el('option', { value: o }, o)));
    const preferred = options.includes(previous) ? previous : this.fields.some((f) => f.name === 'SEQV') && this.set.kind === 'frames' ? 'SEQV' : options[0];
    this.colourSelect.value = preferred;
    const n = this.set.kind === 'frames' ? this.times.length : MODE_STEPS;
    this.slider.max = String(n - 1);
    this.scaleInput.value = String(this.defaultScale());
    this.fit([-5, 10, 3]);
    this.rangeCache = {};
    this.show(this.set.kind === 'frames' ? this.peakFrame(preferred) : MODE_STEPS / 4);
  }

  /** The frame where the colour field (or |U|) is largest: the moment worth seeing first. */
  peakFrame(name) {
    const field = name === 'none' ? '|U|' : name;
    const elementField = this.isElementField(field);
    let best = -Infinity, frame = this.times.length - 1;
    for (let k = 0; k < this.times.length; k++) {
      const n = elementField ? this.nElements : this.nNodes;
      for (let i = 0; i < n; i++) {
        const v = elementField ? this.fieldValue(field, k, 0, i) : this.fieldValue(field, k, i, 0);
        if (Number.isFinite(v) && Math.abs(v) > best) {
          best = Math.abs(v);
          frame = k;
        }
      }
    }
    return frame;
  }

  /** Largest nodal displacement of the set. */
  maxDisplacement() {
    const a = this.set.kind === 'frames' ? this.U : this.modes.subarray(this.set.mode * this.nNodes * 3, (this.set.mode + 1) * this.nNodes * 3);
    let m = 0;
    for (let i = 0; i < a.length; i += 3) {
      const v = magnitude(a[i], a[i + 1], a[i + 2]);
      if (Number.isFinite(v) && v > m) m = v;
    }
    return m;
  }

  /** True scale when the motion is visible (>= 2 % of the model), else 10 % of the model. */
  defaultScale() {
    const m = this.maxDisplacement();
    if (!(m > 0)) return 1;
    if (this.set.kind === 'frames' && m >= 0.02 * this.size) return 1;
    return +niceBelow((0.1 * this.size) / m).toPrecision(3);
  }

  /** Displacement of node i at the current step (NaN-free; absent = 0). */
  disp(i, out) {
    if (this.set.kind === 'frames') {
      const o = (this.step * this.nNodes + i) * 3;
      out[0] = this.U[o] || 0;
      out[1] = this.U[o + 1] || 0;
      out[2] = this.U[o + 2] || 0;
    } else {
      const o = (this.set.mode * this.nNodes + i) * 3;
      const s = Math.sin((2 * Math.PI * this.step) / MODE_STEPS);
      out[0] = (this.modes[o] || 0) * s;
      out[1] = (this.modes[o + 1] || 0) * s;
      out[2] = (this.modes[o + 2] || 0) * s;
    }
    return out;
  }

  /** Value of the colour field at node i or element e for frame/step k (NaN when absent). */
  fieldValue(name, k, node, element) {
    if (name === '|φ| (mode shape)') {
      const o = (this.set.mode * this.nNodes + node) * 3;
      return magnitude(this.modes[o], this.modes[o + 1], this.modes[o + 2]);
    }
    const o = (k * this.nNodes + node) * 3;
    if (name === '|U|') return magnitude(this.U[o], this.U[o + 1], this.U[o + 2]);
    if (name === 'UX') return this.U[o];
    if (name === 'UY') return this.U[o + 1];
    if (name === 'UZ') return this.U[o + 2];
    const f = this.fields.find((x) => x.name === name);
    return f ? f.values[k * this.nElements + element] : NaN;
  }

  isElementField(name) {
    return this.fields.some((f) => f.name === name);
  }

  /** Colour range of a field over every frame (or the current one). */
  range(name) {
    const frameOnly = this.frameRange.checked || this.set.kind === 'mode';
    const key = `${name}|${frameOnly ? this.step : 'all'}|${this.set.kind}${this.set.mode ?? ''}`;
    if (this.rangeCache[key]) return this.rangeCache[key];
    let lo = Infinity, hi = -Infinity;
    const steps = frameOnly || this.set.kind === 'mode' ? [this.set.kind === 'mode' ? 0 : this.step] : this.times.map((_, k) => k);
    const elementField = this.isElementField(name);
    for (const k of steps) {
      const n = elementField ? this.nElements : this.nNodes;
      for (let i = 0; i < n; i++) {
        const v = elementField ? this.fieldValue(name, k, 0, i) : this.fieldValue(name, k, i, 0);
        if (Number.isFinite(v)) {
          lo = Math.min(lo, v);
          hi = Math.max(hi, v);
        }
      }
    }
    return (this.rangeCache[key] = Number.isFinite(lo) ? [lo, hi] : null);
  }

  colourOf(v, r, out, missing = NO_VALUE) {
    if (!r || !Number.isFinite(v)) return out.copy(missing);
    const t = r[1] > r[0] ? (v - r[0]) / (r[1] - r[0]) : 0.5;
    return out.copy(BAND_RGB[Math.min(BANDS.length - 1, Math.max(0, Math.floor(t * BANDS.length)))]);
  }

  show(step) {
    this.step = step;
    this.slider.value = String(step);
    if (this.set.kind === 'frames') {
      const t = this.times[step];
      this.timeLabel.textContent = `t = ${fmt(t, 6)}   (frame ${step + 1} of ${this.times.length})`;
      if (this.onTime) this.onTime(t);
    } else {
      this.timeLabel.textContent = `phase ${Math.round((360 * step) / MODE_STEPS)}°`;
    }
    this.update();
  }

  update(scaleChanged = false) {
    if (!this.renderer || !this.set) return;
    const m = this.data.mesh;
    const scale = Math.max(0, +this.scaleInput.value || 0);
    const name = this.colourSelect.value;
    const r = name === 'none' ? null : this.range(name);
    const elementField = this.isElementField(name);
    const d = [0, 0, 0];
    const pos = new Float32Array(this.nNodes * 3);
    for (let i = 0; i < this.nNodes; i++) {
      this.disp(i, d);
      for (let c = 0; c < 3; c++) pos[3 * i + c] = this.xyz[3 * i + c] + scale * d[c];
    }
    const col = new THREE.Color();
    const fill = (obj, nodes, perItem, elementOf, missing = NO_VALUE) => {
      const p = obj.geometry.attributes.position, cl = obj.geometry.attributes.color;
      for (let k = 0; k < nodes.length; k++) {
        const n = nodes[k];
        p.array.set(pos.subarray(3 * n, 3 * n + 3), 3 * k);
        const e = elementOf[Math.floor(k / perItem)];
        if (name === 'none') col.copy(UNIFORM);
        else this.colourOf(elementField ? this.fieldValue(name, this.step, 0, e) : this.fieldValue(name, this.step, n, e), r, col, missing);
        col.toArray(cl.array, 3 * k);
      }
      p.needsUpdate = true;
      cl.needsUpdate = true;
    };
    fill(this.triMesh, m.triangles, 3, m.triangle_element);
    this.triMesh.geometry.computeVertexNormals();
    fill(this.lineObj, m.lines, 2, m.line_element, NO_VALUE_LINE);
    fill(this.pointObj, m.points, 1, m.point_element);
    const op = this.overlayObj.geometry.attributes.position;
    this.overlayTri.forEach((n, k) => op.array.set(pos.subarray(3 * n, 3 * n + 3), 3 * k));
    op.needsUpdate = true;
    const ep = this.edgeObj.geometry.attributes.position;
    m.edges.forEach((n, k) => ep.array.set(pos.subarray(3 * n, 3 * n + 3), 3 * k));
    ep.needsUpdate = true;
    const mp = this.markerObj.geometry.attributes.position;
    this.markerNodes.forEach((n, k) => mp.array.set(pos.subarray(3 * n, 3 * n + 3), 3 * k));
    mp.needsUpdate = true;
    this.edgeObj.visible = this.edgesBox.checked;
    this.undObj.visible = this.undeformed.checked;
    this.drawLegend(name, r);
    if (scaleChanged) this.rangeCache = this.rangeCache || {};
    this.caption.replaceChildren(
      el('span', { class: 'fig-no' }, 'Deformed shape. '),
      this.set.kind === 'frames' ? `Displacements × ${fmt(scale, 4)} at t = ${fmt(this.times[this.step], 6)}` : `${this.set.label}, shape × ${fmt(scale, 4)}`,
      name === 'none' ? '' : `, coloured by ${name}${elementField ? ' (element values)' : ' (nodal values)'}`,
      this.undeformed.checked ? '; undeformed shape in grey.' : '.',
    );
    this.render();
  }

  drawLegend(name, r) {
    if (name === 'none' || !r) {
      this.legend.replaceChildren(name === 'none' ? '' : el('div', { class: 'legend-title' }, `${name}: no values`));
      return;
    }
    const rows = [];
    for (let b = BANDS.length - 1; b >= 0; b--) {
      const lo = r[0] + ((r[1] - r[0]) * b) / BANDS.length, hi = r[0] + ((r[1] - r[0]) * (b + 1)) / BANDS.length;
      rows.push(el('div', { class: 'legend-band' }, el('span', { class: 'swatch', style: `background:${BANDS[b]}` }), `${fmt(lo)} … ${fmt(hi)}`));
    }
    this.legend.replaceChildren(el('div', { class: 'legend-title' }, name), ...rows, el('div', { class: 'legend-band muted' }, el('span', { class: 'swatch', style: 'background:#b9bec6' }), 'no value'));
  }

  /** Box around the shape at the current scale over every frame (or the mode's swing). */
  deformedBox() {
    const scale = +this.scaleInput.value || 0;
    const box = this.box.clone();
    const v = new THREE.Vector3();
    const d = [0, 0, 0];
    const keep = this.step;
    const steps = this.set.kind === 'frames' ? this.times.length : 2;
    for (let k = 0; k < steps; k++) {
      this.step = this.set.kind === 'frames' ? k : (k ? 3 : 1) * (MODE_STEPS / 4);
      for (const i of this.framed) {
        this.disp(i, d);
        box.expandByPoint(v.set(this.xyz[3 * i] + scale * d[0], this.xyz[3 * i + 1] + scale * d[1], this.xyz[3 * i + 2] + scale * d[2]));
      }
    }
    this.step = keep;
    return box;
  }

  fit(dir) {
    const box = this.deformedBox();
    const c = box.getCenter(new THREE.Vector3());
    const radius = Math.max(0.5 * box.getSize(new THREE.Vector3()).length(), 1e-12);
    const v = this.planarZ && dir[0] === -5 ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(...dir).normalize();
    const distance = (0.85 * radius) / Math.sin((this.camera.fov * Math.PI) / 360);
    this.camera.position.copy(c).addScaledVector(v, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(c);
    this.controls.update();
    this.render();
  }

  resize() {
    if (!this.renderer) return;
    const w = this.viewport.clientWidth, h = this.viewport.clientHeight;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / Math.max(1, h);
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() {
    if (!this.renderer) return;
    const r = this.renderer;
    const w = this.canvas.width / r.getPixelRatio(), h = this.canvas.height / r.getPixelRatio();
    r.setScissorTest(false);
    r.setViewport(0, 0, w, h);
    r.render(this.scene, this.camera);
    this.stats.triangles = r.info.render.triangles;
    this.stats.lines = r.info.render.lines;
    this.stats.points = r.info.render.points;
    this.stats.renders++;
    // Axis triad in the lower left corner, turned with the camera.
    const s = Math.min(110, Math.floor(Math.min(w, h) / 3));
    this.triadCamera.position.set(0, 0, 0).sub(this.controls.target).add(this.camera.position).normalize().multiplyScalar(4);
    this.triadCamera.up.copy(this.camera.up);
    this.triadCamera.lookAt(0, 0, 0);
    r.setScissorTest(true);
    r.setScissor(0, 0, s, s);
    r.setViewport(0, 0, s, s);
    r.autoClear = false;
    r.clearDepth();
    r.render(this.triadScene, this.triadCamera);
    r.autoClear = true;
    r.setScissorTest(false);
  }

  /** Fraction of canvas pixels that are not background (test hook). */
  coveredPixels() {
    if (!this.renderer) return 0;
    this.render();
    const c = document.createElement('canvas');
    c.width = this.canvas.width;
    c.height = this.canvas.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(this.canvas, 0, 0);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    let covered = 0;
    for (let i = 0; i < px.length; i += 4) if (px[i] < 235 || px[i + 1] < 235 || px[i + 2] < 235) covered++;
    return covered / (px.length / 4);
  }

  togglePlay() {
    if (this.timer) return this.stopPlay();
    const n = +this.slider.max + 1;
    if (this.step >= n - 1) this.show(0);
    this.playButton.textContent = 'Pause';
    const period = this.set.kind === 'frames' ? Math.max(16, 6000 / n) : 40;
    this.timer = setInterval(() => {
      const next = this.step + 1;
      if (next >= n) {
        if (this.set.kind === 'mode') this.show(0);
        else this.stopPlay();
      } else this.show(next);
    }, period);
  }

  stopPlay() {
    if (this.timer) clearInterval(this.timer);
    this.timer = null;
    if (this.playButton) this.playButton.textContent = 'Play';
  }
}
