// What BRDF Explorer cannot show: the model's importance sampler at the light's θ_i — the
// directions it draws, seen from above the hemisphere, and its χ² test (check --sampling) as the
// observed and expected histograms over the equal-area grid (cos θ_o rows from the horizon up,
// φ_o columns), with the verdict. Every number is the server's (/api/sampling).
import {api} from './api.js';

/// The histogram as a heat map: each cell's count over the largest expected one, in grey.
function drawHistogram(canvas, counts, bins, top) {
  const width = 2 * bins, context = canvas.getContext('2d'), image = context.createImageData(width, bins);
  for (let row = 0; row < bins; ++row)
    for (let col = 0; col < width; ++col) {
      const g = Math.round(255 * Math.min(1, counts[row * width + col] / top));
      const p = 4 * ((bins - 1 - row) * width + col);  // the horizon at the bottom
      image.data[p] = image.data[p + 1] = image.data[p + 2] = g;
      image.data[p + 3] = 255;
    }
  context.putImageData(image, 0, 0);
}

/// The sampled directions projected on the disc of the hemisphere seen from above (x right, y up).
function drawPoints(canvas, points) {
  const context = canvas.getContext('2d'), r = canvas.width / 2;
  context.fillStyle = '#000';
  context.fillRect(0, 0, canvas.width, canvas.height);
  context.strokeStyle = '#666';
  context.beginPath();
  context.arc(r, r, r - 1, 0, 2 * Math.PI);
  context.stroke();
  context.fillStyle = '#ffd54a';
  for (const [x, y] of points) context.fillRect(r + x * (r - 1) - 1, r - y * (r - 1) - 1, 2, 2);
}

/// Fetches and draws the sampling view for `model` ({request, params, name}) at θ_i = theta.
export async function drawSampling(model, theta, samples) {
  const c = await api('/api/sampling', {model: model.request, params: model.params, theta, samples, bins: 16, points: 1500});
  const bins = c.cos_bins, top = Math.max(1e-12, ...c.expected);
  for (const [id, counts] of [['sampling-observed', c.observed], ['sampling-expected', c.expected]]) {
    const canvas = document.getElementById(id);
    canvas.width = 2 * bins;
    canvas.height = bins;
    drawHistogram(canvas, counts, bins, top);
  }
  drawPoints(document.getElementById('sampling-points'), c.points);
  const verdict = document.getElementById('sampling-verdict');
  verdict.textContent = `${model.name} at θi = ${theta}°, ${c.method}: χ² = ${c.chi2.toPrecision(4)} with ${c.dof} degrees of freedom, ` +
    `p = ${c.p_value.toPrecision(3)} (α = ${c.alpha.toPrecision(2)}): ${c.chi2_passes ? 'passes' : 'fails'}; mean weight ` +
    `${c.mean_weight.toPrecision(5)} ± ${c.standard_error.toPrecision(2)} against the albedo ${c.albedo.toPrecision(5)}; ` +
    `${c.passes ? 'every check passes' : 'a check fails'}.`;
  verdict.className = c.passes ? '' : 'error';
  return c;
}
