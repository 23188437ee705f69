// Time-history figures drawn with uPlot, in the manner of the thesis' POST26 plots: one
// quantity against time, one curve per node or element, axis labels, numbered captions.
import uPlot from 'uplot';
import { el, f32, fmt, palette, tickFormatter } from './util.js';

/** A vertical line at the time shown in the 3-D view. */
function markerPlugin(set) {
  return {
    hooks: {
      draw: [
        (u) => {
          const t = set.markerTime;
          if (t === null || t === undefined) return;
          const x = u.valToPos(t, 'x', true);
          const { left, top, width, height } = u.bbox;
          if (x < left - 0.5 || x > left + width + 0.5) return;
          const ctx = u.ctx;
          ctx.save();
          ctx.strokeStyle = 'rgba(180, 30, 30, 0.75)';
          ctx.lineWidth = 1 * devicePixelRatio;
          ctx.setLineDash([5 * devicePixelRatio, 4 * devicePixelRatio]);
          ctx.beginPath();
          ctx.moveTo(x, top);
          ctx.lineTo(x, top + height);
          ctx.stroke();
          ctx.restore();
        },
      ],
    },
  };
}

export class PlotSet {
  constructor() {
    this.plots = []; // {title, uplot, figure, series: [{label, points}]}
    this.markerTime = null;
    this.figureNumber = 0;
    window.addEventListener('resize', () => this.resize());
  }

  /** Adds a figure {title, xlabel, ylabel, series: [{label, t, y, n, n_stored}]} to `parent`. */
  add(parent, fig, extraSeries = []) {
    const curves = fig.series.map((s) => ({ label: s.label, t: f32(s.t), y: f32(s.y), n: s.n, stored: s.n_stored }));
    const number = ++this.figureNumber;
    const holder = el('div', { class: 'plot' });
    const sampled = curves.some((c) => c.stored > c.n);
    const stored = Math.max(...curves.map((c) => c.stored));
    const caption = el(
      'figcaption',
      null,
      el('span', { class: 'fig-no' }, `Fig. ${number}. `),
      fig.title,
      el('span', { class: 'fig-note' }, sampled ? ` (${stored} stored points per curve, drawn min/max-sampled)` : ` (${stored} stored points)`),
    );
    const figure = el('figure', { class: 'figure', id: `fig-${number}` }, holder, caption);
    parent.appendChild(figure);

    const aligned = uPlot.join(curves.map((c) => [Array.from(c.t), Array.from(c.y)]));
    const opts = {
      width: this.widthOf(holder),
      height: 300,
      scales: { x: { time: false } },
      legend: { live: true },
      cursor: { sync: { key: 'impactfe' }, drag: { x: true, y: false } },
      axes: [
        axis(fig.xlabel || 'Time'),
        Object.assign(axis(fig.ylabel), { size: fig.axisSize || 78 }),
      ],
      series: [
        { label: fig.xlabel || 'Time', value: (u, v) => fmt(v, 6) },
        ...curves.map((c, i) => ({
          label: c.label,
          stroke: palette[i % palette.length],
          width: 1.5,
          spanGaps: true,
          points: { show: c.n < 60, size: 4 },
          value: (u, v) => fmt(v, 5),
        })),
      ],
      plugins: [markerPlugin(this)],
      hooks: { setScale: [(u, key) => key === 'x' && this.syncX(u)] },
    };
    const plot = new uPlot(opts, aligned, holder);
    const entry = {
      title: fig.title,
      uplot: plot,
      holder,
      series: curves.map((c) => ({ label: c.label, points: countFinite(c.y) })),
    };
    this.plots.push(entry);
    return entry;
  }

  /** A zoom of one plot's time axis (drag, double-click reset) applies to every plot. */
  syncX(source) {
    if (!this.live || this.syncing) return;
    this.syncing = true;
    const { min, max } = source.scales.x;
    for (const p of this.plots) if (p.uplot !== source) p.uplot.setScale('x', { min, max });
    if (this.onWindow) this.onWindow(min, max);
    this.syncing = false;
  }

  /** Shows the time window [min, max] in every plot. */
  setWindow(min, max) {
    if (!this.plots.length) {
      if (this.onWindow) this.onWindow(min, max);
      return;
    }
    this.plots[0].uplot.setScale('x', { min, max });
  }

  /** Left and right margins of a plot's drawing area in CSS pixels (to align other charts). */
  margins(entry) {
    const u = entry.uplot, dpr = window.devicePixelRatio || 1;
    return { left: u.bbox.left / dpr, right: u.width - (u.bbox.left + u.bbox.width) / dpr };
  }

  widthOf(holder) {
    return Math.max(320, Math.floor(holder.getBoundingClientRect().width || holder.parentElement.clientWidth || 560));
  }

  resize() {
    for (const p of this.plots) p.uplot.setSize({ width: this.widthOf(p.holder), height: p.uplot.height });
  }

  setMarker(t) {
    this.markerTime = t;
    for (const p of this.plots) p.uplot.redraw(false, false);
  }
}

function axis(label) {
  return {
    label,
    labelSize: 22,
    labelFont: '600 13px system-ui, sans-serif',
    font: '12px system-ui, sans-serif',
    stroke: '#222',
    grid: { stroke: '#e3e3e3', width: 1 },
    ticks: { stroke: '#888', width: 1, size: 5 },
    values: (u, splits) => tickFormatter(splits),
  };
}

function countFinite(a) {
  let n = 0;
  for (const v of a) if (Number.isFinite(v)) n++;
  return n;
}
