// Small SVG plots: lines against x (linear or log axes) and polar curves, with a legend.
const NS = 'http://www.w3.org/2000/svg';
export const palette = ['#d62728', '#1f77b4', '#2ca02c', '#9467bd', '#7f7f7f'];

function element(name, attributes, text) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

const finite = (v) => typeof v === 'number' && Number.isFinite(v);

function extent(values, log) {
  const usable = values.filter((v) => finite(v) && (!log || v > 0));
  if (!usable.length) return [0, 1];
  let lo = Math.min(...usable), hi = Math.max(...usable);
  if (!log) lo = Math.min(lo, 0);
  if (hi === lo) hi = lo + (log ? lo : 1);
  return [lo, hi];
}

function legend(svg, series, x, y) {
  series.forEach((s, i) => {
    svg.append(element('rect', {x, y: y + 14 * i, width: 10, height: 3, fill: s.colour}));
    svg.append(element('text', {x: x + 14, y: y + 14 * i + 5, 'font-size': 11}, s.name));
  });
}

const kBox = {W: 360, H: 230, L: 48, R: 10, T: 10, B: 34};  // the plots' size and margins

/// The frame, end ticks and axis labels of a plot of [x0, x1] × [y0, y1] (options.logX, logY:
/// log axes), its marks `pad` pixels inside the frame; returns px and py, values to pixels.
function axes(svg, [x0, x1], [y0, y1], options, pad = 0) {
  const {W, H, L, R, T, B} = kBox;
  const at = (v, lo, hi, log) => (hi > lo ? (log ? (Math.log10(v) - Math.log10(lo)) / (Math.log10(hi) - Math.log10(lo)) : (v - lo) / (hi - lo)) : 0.5);
  const px = (v) => L + pad + at(v, x0, x1, options.logX) * (W - L - R - 2 * pad);
  const py = (v) => H - B - pad - at(v, y0, y1, options.logY) * (H - T - B - 2 * pad);
  svg.append(element('rect', {x: L, y: T, width: W - L - R, height: H - T - B, fill: 'none', stroke: '#999'}));
  for (const [v, anchor] of [[x0, 'start'], [x1, 'end']])
    svg.append(element('text', {x: px(v), y: H - B + 13, 'font-size': 10, 'text-anchor': anchor}, +v.toPrecision(3)));
  for (const v of [y0, y1]) svg.append(element('text', {x: L - 3, y: py(v) + 4, 'font-size': 10, 'text-anchor': 'end'}, +v.toPrecision(3)));
  svg.append(element('text', {x: (L + W - R) / 2, y: H - 4, 'font-size': 11, 'text-anchor': 'middle'}, options.xLabel || ''));
  svg.append(element('text', {x: 12, y: (T + H - B) / 2, 'font-size': 11, 'text-anchor': 'middle', transform: `rotate(-90 12 ${(T + H - B) / 2})`}, options.yLabel || ''));
  return {px, py};
}

/// series: [{name, colour, xs, ys, dashed}] (a dashed one is left out of the legend);
/// options: {xLabel, yLabel, logX, logY}.
export function linePlot(container, series, options = {}) {
  const svg = element('svg', {viewBox: `0 0 ${kBox.W} ${kBox.H}`, role: 'img', 'aria-label': options.title || options.yLabel || 'plot'});
  const {px, py} = axes(svg, extent(series.flatMap((s) => s.xs), options.logX), extent(series.flatMap((s) => s.ys), options.logY), options);
  for (const s of series) {
    const points = s.xs.map((x, i) => [x, s.ys[i]]).filter(([x, y]) => finite(x) && finite(y) && (!options.logX || x > 0) && (!options.logY || y > 0));
    if (points.length)
      svg.append(element('polyline', {points: points.map(([x, y]) => `${px(x).toFixed(1)},${py(y).toFixed(1)}`).join(' '), fill: 'none', stroke: s.colour,
                                      'stroke-width': s.dashed ? 1 : 1.6, ...(s.dashed ? {'stroke-dasharray': '4 3', class: 'band'} : {})}));
  }
  legend(svg, series.filter((s) => !s.dashed), kBox.W - kBox.R - 150, kBox.T + 8);
  container.replaceChildren(svg);
}

/// series: [{name, colour, degrees (from the normal, negative toward the light's side), values}].
export function polarPlot(container, series, options = {}) {
  const W = 360, H = 230, cx = W / 2, cy = H - 20, radius = H - 40;
  const svg = element('svg', {viewBox: `0 0 ${W} ${H}`, role: 'img', 'aria-label': options.title || 'polar plot'});
  const max = Math.max(1e-12, ...series.flatMap((s) => s.values.filter(finite)));
  svg.append(element('path', {d: `M ${cx - radius} ${cy} A ${radius} ${radius} 0 0 1 ${cx + radius} ${cy} Z`, fill: 'none', stroke: '#bbb'}));
  svg.append(element('line', {x1: cx, y1: cy, x2: cx, y2: cy - radius, stroke: '#ddd'}));
  if (options.lightDeg !== undefined) {  // the incident direction (left) and its mirror (right)
    const a = (options.lightDeg * Math.PI) / 180;
    for (const [side, name, colour] of [[-1, 'incident', '#e6a700'], [1, 'mirror', '#777']]) {
      const x2 = cx + side * radius * Math.sin(a), y2 = cy - radius * Math.cos(a);
      svg.append(element('line', {x1: cx, y1: cy, x2, y2, stroke: colour, 'stroke-dasharray': '4 3', class: name}));
      svg.append(element('text', {x: x2, y: y2 - 3, 'font-size': 10, fill: colour, 'text-anchor': side < 0 ? 'end' : 'start'}, name));
    }
  }
  for (const s of series) {
    const points = s.degrees.map((d, i) => {
      const r = (finite(s.values[i]) ? s.values[i] : 0) / max * radius, a = (d * Math.PI) / 180;
      return `${(cx + r * Math.sin(a)).toFixed(1)},${(cy - r * Math.cos(a)).toFixed(1)}`;
    });
    svg.append(element('polyline', {points: points.join(' '), fill: 'none', stroke: s.colour, 'stroke-width': 1.6}));
  }
  svg.append(element('text', {x: 4, y: 12, 'font-size': 10}, `max ${+max.toPrecision(3)}`));
  legend(svg, series, W - 150, 10);
  container.replaceChildren(svg);
}

/// points: [{x, y, label, reference, onPick}]: a scatter of the error y (log axis; an error of 0
/// drawn at a tenth of the least positive one) against the cost x (linear; a point without one is
/// left out), a point with onPick a focusable button (click, Enter or Space picks it), references grey.
export function paretoPlot(container, points, options = {}) {
  const svg = element('svg', {viewBox: `0 0 ${kBox.W} ${kBox.H}`, role: 'group', 'aria-label': options.title || 'Pareto front'});
  const positive = points.map((p) => p.y).filter((y) => finite(y) && y > 0);
  const floor = positive.length ? Math.min(...positive) / 10 : 1e-12;
  const usable = points.filter((p) => finite(p.x) && finite(p.y)).map((p) => ({...p, y: Math.max(p.y, floor)}));
  const {px, py} = axes(svg, extent(usable.map((p) => p.x), false), extent(usable.map((p) => p.y), true),
                        {xLabel: 'cost', yLabel: 'error', ...options, logY: true}, 8);
  for (const p of usable) {
    const mark = element('circle', {cx: px(p.x), cy: py(p.y), r: 5, fill: p.reference ? '#999' : '#1f77b4', class: p.reference ? 'reference' : 'member'});
    mark.append(element('title', {}, p.label));
    if (p.onPick) {
      mark.setAttribute('tabindex', '0');
      mark.setAttribute('role', 'button');
      mark.setAttribute('aria-label', p.label);
      mark.style.cursor = 'pointer';
      mark.addEventListener('click', p.onPick);
      mark.addEventListener('keydown', (e) => { if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); p.onPick(); } });
    }
    svg.append(mark);
  }
  container.replaceChildren(svg);
}
