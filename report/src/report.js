// The impactfe report page: reads the run's data (JSON written by report_data.cpp, schema in
// docs/report.md) and builds the summary, the 3-D view, the time-history figures, the energy
// balance, the gap status timeline and the modal table. window.impactfeReport is the test hook.
import { GapTimeline } from './gaps.js';
import { PlotSet } from './plots.js';
import { el, fmt } from './util.js';
import { View3D } from './view3d.js';

/* global __LIBRARIES__ */
const errors = [];
window.addEventListener('error', (e) => errors.push(String(e.message || e)));

const ENERGY_LABELS = {
  kinetic: 'Kinetic energy T',
  strain: 'Strain energy U',
  external_work: 'External work W',
  gap_work: 'Gap work Wg',
  dissipation: 'Damping dissipation D',
  plastic_work: 'Plastic work Wp',
  numerical_dissipation: 'Numerical dissipation T0 + W − (T+U+Wg+D+Wp)',
  initial_kinetic: 'Initial kinetic energy T0 (IC)',
};

const ATTRIBUTE_LABELS = {
  wall_seconds: ['wall time', ' s'],
  factorizations: ['factorizations', ''],
  dofs: ['DOFs', ''],
  n_dofs: ['DOFs', ''],
  iterations: ['iterations', ''],
  substeps: ['substeps', ''],
  status_changes: ['gap status changes', ''],
  time_step: ['Δt', ''],
  masters: ['master DOFs', ''],
  slaves: ['slave DOFs', ''],
  gap_conditions: ['gap conditions', ''],
  modes: ['modes', ''],
};

function attributeText(analysis) {
  const parts = [];
  for (const [name, value] of Object.entries(analysis.numeric || {})) {
    const [label, unit] = ATTRIBUTE_LABELS[name] || [name.replace(/_/g, ' '), ''];
    parts.push(`${label} ${Number.isInteger(value) ? value : fmt(value, 4)}${unit}`);
  }
  for (const [name, value] of Object.entries(analysis.text || {})) parts.push(`${name.replace(/_/g, ' ')}: ${value}`);
  return parts.join(' · ');
}

function table(headers, rows, cls = 'data') {
  return el('table', { class: cls }, el('thead', null, el('tr', null, headers.map((h) => el('th', null, h)))), el('tbody', null, rows.map((r) => el('tr', null, r.map((c) => (c instanceof Node ? el('td', null, c) : el('td', null, String(c))))))));
}

function summary(section, data) {
  const counts = {};
  for (const t of data.mesh.element_types) counts[t] = (counts[t] || 0) + 1;
  const typeText = Object.entries(counts).map(([t, n]) => `${n} ${t}`).join(', ');
  section.appendChild(
    el('dl', { class: 'facts' },
      el('dt', null, 'Title'), el('dd', null, data.title || '–'),
      el('dt', null, 'Results file'), el('dd', { class: 'mono' }, data.file),
      el('dt', null, 'Model'), el('dd', null, `${data.n_nodes} nodes, ${data.n_elements} elements (${typeText || 'none'})`),
      el('dt', null, 'Parts'), el('dd', null, data.mesh.bodies.map((b) => (b.name.startsWith('node ') ? b.name : `${b.name} (${b.n_nodes} nodes)`)).join('; ') || '–'),
    ),
  );
  const rows = data.analyses.map((a) => [
    String(a.index),
    a.kind.replace(/_/g, ' '),
    a.description || '–',
    el('span', { class: `status ${a.status === 'complete' ? 'ok' : 'bad'}` }, a.status),
    String(a.n_time_points),
    a.n_time_points ? `${fmt(a.time_first, 5)} … ${fmt(a.time_last, 5)}` : '–',
    attributeText(a) || '–',
  ]);
  section.appendChild(table(['#', 'Analysis', 'Description', 'Status', 'Stored points', 'Time range', 'Statistics'], rows));
}

/** Run time range and the time the first gap closes (null when none does). */
function timeRange(data) {
  let t0 = Infinity, t1 = -Infinity;
  for (const a of data.analyses) if (a.n_time_points && a.kind !== 'modal') { t0 = Math.min(t0, a.time_first); t1 = Math.max(t1, a.time_last); }
  let contact = Number.isFinite(data.first_contact_time) ? data.first_contact_time : Infinity;
  for (const r of data.gap_status.rows) for (const [t, s] of r.changes) if (s === 1 || s === 2) contact = Math.min(contact, t);
  return { t0, t1, contact: Number.isFinite(contact) && contact > t0 ? contact : null };
}

function windowControls(data, plots) {
  const { t0, t1, contact } = timeRange(data);
  const buttons = [el('button', { type: 'button', class: 'btn small', onclick: () => plots.setWindow(t0, t1) }, 'Whole run')];
  if (contact !== null) {
    const from = Math.max(t0, contact - 0.1 * (t1 - contact));
    buttons.push(el('button', { type: 'button', class: 'btn small', onclick: () => plots.setWindow(from, t1) }, `Contact phase (t ≥ ${fmt(from, 4)})`));
  }
  return el('div', { class: 'ctl-row small window-row' }, 'Time window of all figures: ', buttons, el('span', null, ' · drag across a figure to zoom, double-click to reset'));
}

function energy(section, data, plots) {
  for (const e of data.energy) {
    const u = data.units || {};
    const fig = { title: `Energy balance of analysis ${e.analysis} (${e.description}) vs time`, xlabel: u.time ? `Time (${u.time})` : 'Time', ylabel: u.energy ? `Energy (${u.energy})` : 'Energy', series: e.curves.map((c) => Object.assign({}, c, { label: ENERGY_LABELS[c.label] || c.label })) };
    const grid = el('div', { class: 'grid one' });
    section.appendChild(grid);
    plots.add(grid, fig);
    const f = e.final;
    // The energy put in: the external work and the kinetic energy of the initial velocities.
    const t0 = f.initial_kinetic || 0;
    const w = (f.external_work || 0) + t0;
    const input = t0 ? 'T0 + W' : 'W';
    const order = ['initial_kinetic', ...Object.keys(f).filter((k) => k !== 'initial_kinetic')];
    const rows = order.filter((k) => k in f).map((k) => [ENERGY_LABELS[k] || k, fmt(f[k], 5), w ? `${fmt((100 * f[k]) / w, 3)} %` : '–']);
    section.appendChild(el('p', { class: 'table-caption' }, `Energies at the end, t = ${fmt(e.time_final, 6)} (share of the energy put in, ${input}):`));
    section.appendChild(table(['Term', 'Value', `Share of ${input}`], rows, 'data narrow'));
    const share = w ? Math.abs(f.numerical_dissipation / w) : 0;
    if (share > 0.05) section.appendChild(el('p', { class: 'warning' }, `The time integrator removed ${fmt(100 * share, 3)} % of the energy put in (numerical dissipation above 5 %): a smaller time step or another integrator (Newmark, HHT-α) gives a more faithful balance.`));
  }
}

function histories(section, data, plots) {
  const sel = data.selection || {};
  const dirs = (data.directions || []).join(', ');
  section.appendChild(
    el('p', { class: 'lead' },
      sel.nodes_auto ? 'Nodes picked automatically: for each part, the node with the largest displacement and the moving nodes of gap elements (at most four). ' : 'Nodes chosen with --node. ',
      dirs ? (sel.directions_auto ? `Directions ${dirs}: those whose peak displacement is at least 10 % of the largest. ` : `Directions ${dirs} (--item). `) : '',
      sel.elements_auto ? 'Elements: the most stressed element of each element type. ' : 'Elements chosen with --element. ',
      'Other choices: impactfe report FILE --node N --element E --item LAB.'),
  );
  const order = { Displacement: 0, Velocity: 1, Acceleration: 2 };
  const nodal = data.figures.filter((f) => f.group === 'nodal');
  const quantity = (f) => order[f.ylabel.split(' ')[0]] ?? 3;
  nodal.sort((a, b) => quantity(a) - quantity(b));
  section.appendChild(windowControls(data, plots));
  const grid = el('div', { class: 'grid' });
  section.appendChild(grid);
  for (const f of [...nodal, ...data.figures.filter((f) => f.group !== 'nodal')]) plots.add(grid, f);
  if (!data.figures.length) section.appendChild(el('p', { class: 'note' }, 'No time histories are stored in this file.'));
}

function gaps(section, data, plots) {
  // The timeline shares the time axis of the gap-force figure (same left and right margins).
  let margins = () => ({ left: 190, right: 16 });
  if (data.gap_force) {
    const grid = el('div', { class: 'grid one' });
    section.appendChild(grid);
    const entry = plots.add(grid, Object.assign({ axisSize: 168 }, data.gap_force));
    margins = () => plots.margins(entry);
  }
  const rows = data.gap_status.rows;
  if (!rows.length) return null;
  const { t0, t1 } = timeRange(data);
  const shown = data.gap_status.n_gaps > rows.length ? ` (${rows.length} of ${data.gap_status.n_gaps} gaps)` : '';
  const caption = el('figcaption', null, el('span', { class: 'fig-no' }, 'Gap status. '), `Status of every gap over time${shown}: STAT of COMBIN40 elements; a GP gap condition is shown closed while its force is non-zero.`);
  return new GapTimeline(section, rows, t0, t1, caption, margins);
}

function contacts(section, data, plots) {
  section.appendChild(el('p', { class: 'lead' }, 'Total force of each contact pair (the contact elements of one real set): the normal force ΣFN and the friction force ΣFT summed over its contact elements, the pair with the largest normal force first. Gap elements (COMBIN40, CONTA178) are in their own section.'));
  const grid = el('div', { class: 'grid' });
  section.appendChild(grid);
  for (const f of data.contact_force) plots.add(grid, f);
}

function modes(section, data) {
  const f = data.modes.frequencies;
  const rows = f.map((hz, i) => [String(i + 1), fmt(hz, 6), fmt(2 * Math.PI * hz, 6), hz > 0 ? fmt(1 / hz, 6) : '–']);
  section.appendChild(table(['Mode', 'Frequency f (Hz)', 'Circular frequency ω = 2πf (rad/s)', 'Period T = 1/f'], rows, 'data narrow'));
  if (data.modes.n_shapes) section.appendChild(el('p', { class: 'note' }, 'The mode shapes can be animated in the deformed-shape view (Result: Mode n).'));
}

/** Pixels of saturated colour (the curves) in a uPlot canvas. */
function inkPixels(plot) {
  const c = plot.uplot.ctx.canvas;
  const px = plot.uplot.ctx.getImageData(0, 0, c.width, c.height).data;
  let n = 0;
  for (let i = 0; i < px.length; i += 4) {
    const hi = Math.max(px[i], px[i + 1], px[i + 2]), lo = Math.min(px[i], px[i + 1], px[i + 2]);
    if (px[i + 3] > 0 && hi - lo > 60) n++;
  }
  return n;
}

function main() {
  const data = JSON.parse(document.getElementById('impactfe-data').textContent);
  const hook = (window.impactfeReport = { ready: false, data, errors });
  const root = document.getElementById('report');
  const nav = document.getElementById('doc-nav');
  const sections = [];
  const section = (id, title) => {
    const number = sections.length + 1;
    const s = el('section', { id, class: 'section' }, el('h2', null, el('span', { class: 'sec-no' }, `${number}`), title));
    root.appendChild(s);
    sections.push(s);
    nav.appendChild(el('a', { href: `#${id}` }, `${number} ${title}`));
    return s;
  };
  document.getElementById('doc-meta').textContent = `${data.file} · ${data.analyses.length} analys${data.analyses.length === 1 ? 'is' : 'es'} · ${data.n_nodes} nodes · ${data.n_elements} elements`;

  const plots = new PlotSet();
  summary(section('summary', 'Run summary'), data);
  const shape = section('shape', 'Deformed shape');
  if (data.figures.length) histories(section('histories', 'Time histories'), data, plots);
  if (data.energy.length) energy(section('energy', 'Energy balance'), data, plots);
  let timeline = null;
  if ((data.contact_force || []).length) contacts(section('contact', 'Contact'), data, plots);
  if (data.gap_force || data.gap_status.rows.length) timeline = gaps(section('gaps', 'Gaps'), data, plots);
  if (data.modes.frequencies.length) modes(section('modes', 'Modal results'), data);
  const view = new View3D(shape, data, (t) => {
    plots.setMarker(t);
    if (timeline) timeline.setMarker(t);
  });
  document.getElementById('doc-footer').textContent = `Written by impactfe report from ${data.file}. Plots: ${__LIBRARIES__}; all inlined, the page needs no network.`;

  plots.live = true;
  plots.onWindow = (min, max) => timeline && timeline.setWindow(min, max);
  hook.view = view;
  hook.plots = plots;
  hook.stats = () => ({
    ready: hook.ready,
    webgl: view.stats.webgl,
    triangles: view.stats.triangles,
    lines: view.stats.lines,
    points: view.stats.points,
    meshTriangles: data.mesh.triangles.length / 3,
    overlayTriangles: (data.mesh.overlay_triangles || []).length / 3,
    coveredPixels: view.coveredPixels(),
    frames: (data.frames.times || []).length,
    plots: plots.plots.map((p) => ({ title: p.title, width: p.uplot.width, height: p.uplot.height, series: p.series, inkPixels: inkPixels(p) })),
    gapRows: timeline ? timeline.rows.length : 0,
    gapSegments: timeline ? timeline.segments : 0,
    modeRows: data.modes.frequencies.length,
    errors: errors.slice(),
  });
  // uPlot lays its axes out on the next frame: then align the timeline and mark the page ready.
  requestAnimationFrame(() =>
    requestAnimationFrame(() => {
      if (timeline) timeline.draw();
      hook.ready = true;
    }),
  );
}

try {
  main();
} catch (e) {
  errors.push(String(e && e.stack ? e.stack : e));
  console.error(e);
  document.getElementById('report').appendChild(el('p', { class: 'warning' }, `The report could not be drawn: ${e.message}`));
}
