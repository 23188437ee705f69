// Gap status timeline: one row per gap (COMBIN40 element or GP gap condition), coloured by its
// status over time (STAT: 0 open, 1 closed, 2 sliding; a GP gap is closed while its force is
// non-zero). Drawn on a canvas; the time axis matches the time-history figures.
import { el, fmt } from './util.js';

const STATE = [
  { name: 'open', colour: '#e4e9f0' },
  { name: 'closed', colour: '#0072B2' },
  { name: 'sliding', colour: '#E69F00' },
];

/** "Nice" axis ticks between a and b. */
export function niceTicks(a, b, count = 7) {
  const span = b - a;
  if (!(span > 0)) return [a];
  const raw = span / count;
  const mag = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => span / s <= count) || 10 * mag;
  const ticks = [];
  for (let t = Math.ceil(a / step - 1e-9) * step; t <= b + step * 1e-9; t += step) ticks.push(+t.toPrecision(12));
  return ticks;
}

export class GapTimeline {
  constructor(parent, rows, t0, t1, caption, margins) {
    this.margins = margins || (() => ({ left: 190, right: 16 }));
    this.rows = rows;
    this.t0 = this.first = t0;
    this.t1 = this.last = t1 > t0 ? t1 : t0 + 1;
    this.marker = null;
    this.canvas = el('canvas', { class: 'timeline', role: 'img', 'aria-label': 'gap status timeline' });
    const legend = el(
      'div',
      { class: 'legend-row', style: `margin-left:${this.margins().left}px` },
      STATE.map((s) => el('span', { class: 'swatch-item' }, el('span', { class: 'swatch', style: `background:${s.colour}` }), s.name)),
    );
    this.figure = el('figure', { class: 'figure wide' }, this.canvas, legend, caption);
    parent.appendChild(this.figure);
    this.segments = 0;
    window.addEventListener('resize', () => this.draw());
    this.draw();
  }

  /** Time window of the plots (zoom). */
  setWindow(min, max) {
    this.t0 = Number.isFinite(min) ? min : this.first;
    this.t1 = Number.isFinite(max) && max > this.t0 ? max : this.last;
    this.draw();
  }

  setMarker(t) {
    this.marker = t;
    this.draw();
  }

  draw() {
    const rowH = 18, top = 10, axisH = 40;
    const { left, right } = this.margins();
    const width = Math.max(400, this.figure.clientWidth || 800);
    const height = top + this.rows.length * rowH + axisH;
    const dpr = window.devicePixelRatio || 1;
    const c = this.canvas;
    c.width = width * dpr;
    c.height = height * dpr;
    c.style.width = `${width}px`;
    c.style.height = `${height}px`;
    const ctx = c.getContext('2d');
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, width, height);
    const plotW = width - left - right;
    const x = (t) => left + ((t - this.t0) / (this.t1 - this.t0)) * plotW;
    ctx.font = '12px system-ui, sans-serif';
    ctx.textBaseline = 'middle';
    this.segments = 0;
    this.rows.forEach((row, r) => {
      const y = top + r * rowH;
      ctx.fillStyle = '#222';
      ctx.textAlign = 'right';
      ctx.fillText(row.label, left - 8, y + rowH / 2);
      const ch = row.changes;
      for (let i = 0; i < ch.length; i++) {
        const [ta, s] = ch[i];
        const tb = i + 1 < ch.length ? ch[i + 1][0] : this.last;
        const st = STATE[s] || null;
        ctx.fillStyle = st ? st.colour : '#ffffff';
        const xa = Math.max(left, x(ta)), xb = Math.min(left + plotW, Math.max(x(tb), xa + 1));
        if (xb <= xa) continue;
        ctx.fillRect(xa, y + 2, xb - xa, rowH - 4);
        this.segments++;
      }
    });
    // Time axis.
    const yAxis = top + this.rows.length * rowH + 2;
    ctx.strokeStyle = '#888';
    ctx.beginPath();
    ctx.moveTo(left, yAxis);
    ctx.lineTo(left + plotW, yAxis);
    ctx.stroke();
    ctx.fillStyle = '#222';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    for (const t of niceTicks(this.t0, this.t1)) {
      const xt = x(t);
      ctx.beginPath();
      ctx.moveTo(xt, yAxis);
      ctx.lineTo(xt, yAxis + 5);
      ctx.stroke();
      ctx.fillText(fmt(t, 5), xt, yAxis + 7);
    }
    ctx.font = '600 13px system-ui, sans-serif';
    ctx.fillText('Time', left + plotW / 2, yAxis + 22);
    if (this.marker !== null && this.marker >= this.t0 && this.marker <= this.t1) {
      ctx.strokeStyle = 'rgba(180, 30, 30, 0.75)';
      ctx.setLineDash([5, 4]);
      ctx.beginPath();
      ctx.moveTo(x(this.marker), top);
      ctx.lineTo(x(this.marker), yAxis);
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }
}
