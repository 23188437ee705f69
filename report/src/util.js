// Small helpers of the report page: data decoding, number formatting, DOM building.

/** Little-endian float32 values stored as base64 by the C++ side (report_data.cpp). */
export function f32(b64) {
  if (!b64) return new Float32Array(0);
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}

/** A number for tables and labels: 4 significant digits, exponent for very large/small. */
export function fmt(v, digits = 4) {
  if (v === null || v === undefined || Number.isNaN(v)) return '–';
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e5 || a < 1e-3)) return v.toExponential(digits - 1).replace('e+', 'e');
  return String(+v.toPrecision(digits));
}

/** Tick labels that share one notation across an axis. */
export function tickFormatter(splits) {
  let big = 0;
  for (const v of splits) if (v != null) big = Math.max(big, Math.abs(v));
  if (big !== 0 && (big >= 1e5 || big < 1e-2)) {
    return splits.map((v) => (v == null ? '' : v === 0 ? '0' : v.toExponential(2).replace('e+', 'e')));
  }
  return splits.map((v) => (v == null ? '' : String(+v.toPrecision(6))));
}

/** el('div', {class: 'x'}, child, 'text', ...) */
export function el(tag, attrs, ...children) {
  const node = document.createElement(tag);
  if (attrs) {
    for (const [k, v] of Object.entries(attrs)) {
      if (v === undefined || v === null || v === false) continue;
      if (k === 'class') node.className = v;
      else if (k.startsWith('on')) node.addEventListener(k.slice(2), v);
      else node.setAttribute(k, v === true ? '' : v);
    }
  }
  for (const c of children.flat()) {
    if (c === null || c === undefined || c === false) continue;
    node.appendChild(typeof c === 'string' || typeof c === 'number' ? document.createTextNode(String(c)) : c);
  }
  return node;
}

/** Line colours of the figures: distinct in print and for colour-blind readers (Okabe–Ito). */
export const palette = ['#0072B2', '#D55E00', '#009E73', '#CC79A7', '#E69F00', '#56B4E9', '#000000', '#999933'];
