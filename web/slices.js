// BRDF Explorer's half/difference views (Rusinkiewicz 1998, "A New Change of Variables for
// Efficient BRDF Representation"): f against θ_h at one θ_d, against θ_d at one θ_h, and each
// model's θ_h × θ_d image at φ_d with an exposure and a gamma. Every value is the server's
// (/api/slice); docs/serve.md states the image's mapping, which the tests recompute in C++.
import {api, column} from './api.js';
import {linePlot} from './plots.js';

/// Pixels per side of the image: column i is θ_h = (i + ½)·90/N degrees, row j (top first) θ_d.
export const kImageSize = 64;
const pixelAngles = Array.from({length: kImageSize}, (_, i) => ((i + 0.5) * 90) / kImageSize);
const degrees = Array.from({length: 90}, (_, i) => i);

/// The 8-bit grey of a value: round(255 · min(1, (max(0, v) · 2^exposure)^(1/gamma))).
export function grey(v, exposure, gamma) {
  const x = Math.max(0, v) * 2 ** exposure;
  return Math.round(255 * Math.min(1, x ** (1 / gamma)));
}

/// channels: the values of R, G and B (one array, the same for all three: grey), each θ_h-major,
/// values[i·N + j] at column i (θ_h), row j (θ_d).
function drawImage(canvas, channels, exposure, gamma) {
  const n = kImageSize, context = canvas.getContext('2d'), image = context.createImageData(n, n);
  for (let i = 0; i < n; ++i)
    for (let j = 0; j < n; ++j) {
      const p = 4 * (j * n + i);
      for (let c = 0; c < 3; ++c) image.data[p + c] = grey(channels[c % channels.length][i * n + j], exposure, gamma);
      image.data[p + 3] = 255;
    }
  context.putImageData(image, 0, 0);
}

/// The section's views for `models` ({request, params, name, colour, channelParams}); `settings`
/// holds theta_h, theta_d, phi_d (degrees), exposure (stops), gamma and chroma: with chroma, a model
/// whose parameters differ per channel (channelParams: R's, G's and B's) gets a colour image, each
/// channel from its own parameters (BRDF Explorer's chroma toggle); else the image is grey. Returns what redraw() needs to show a new
/// exposure or gamma without asking the server again. `ask` sends a request (api, or the page's
/// channel's).
export async function fetchSlices(models, settings, ask = api) {
  const at = (m, theta_h, theta_d) => ask('/api/slice', {model: m.request, params: m.params, theta_h, theta_d, phi_d: settings.phi_d});
  return Promise.all(models.map(async (m) => {
    const colour = settings.chroma && m.channelParams;
    const image = (params) => api('/api/slice', {model: m.request, params, theta_h: pixelAngles, theta_d: pixelAngles, phi_d: settings.phi_d});
    const [alongH, alongD, ...images] = await Promise.all([
      at(m, degrees, [settings.theta_d]), at(m, [settings.theta_h], degrees),
      ...(colour ? m.channelParams.map(image) : [at(m, pixelAngles, pixelAngles)])]);
    return {...m, h: column(alongH, 'value'), d: column(alongD, 'value'), image: images.map((t) => column(t, 'value'))};
  }));
}

/// N·L at the half/difference angles (degrees): L's height, cos θ_d cos θ_h − sin θ_d cos φ_d sin θ_h.
const cosL = (theta_h, theta_d, phi_d) => {
  const r = Math.PI / 180;
  return Math.cos(theta_d * r) * Math.cos(theta_h * r) - Math.sin(theta_d * r) * Math.cos(phi_d * r) * Math.sin(theta_h * r);
};

/// Draws the two plots and the images into the section (#plot-theta-h, #plot-theta-d, #slice-images);
/// `shown(ys, cosines)` is what the page's plot switches make of f (× N·L, log10(x + 1)), the
/// images show f itself.
export function drawSlices(slices, settings, shown = (ys) => ys) {
  const cosines = {
    h: degrees.map((d) => cosL(d, settings.theta_d, settings.phi_d)),
    d: degrees.map((d) => cosL(settings.theta_h, d, settings.phi_d)),
  };
  const series = (key) => slices.map((s) => ({name: s.name, colour: s.colour, xs: degrees, ys: shown(s[key], cosines[key])}));
  linePlot(document.getElementById('plot-theta-h'), series('h'), {xLabel: `θh (degrees), θd = ${settings.theta_d}°`, yLabel: 'f'});
  linePlot(document.getElementById('plot-theta-d'), series('d'), {xLabel: `θd (degrees), θh = ${settings.theta_h}°`, yLabel: 'f'});
  document.getElementById('slice-images').replaceChildren(...slices.map((s, i) => {
    const figure = document.createElement('figure');
    const canvas = Object.assign(document.createElement('canvas'), {id: `slice-${i}`, width: kImageSize, height: kImageSize, className: 'slice'});
    canvas.setAttribute('aria-label', `θh × θd image of ${s.name}`);
    drawImage(canvas, s.image, settings.exposure, settings.gamma);
    canvas.dataset.chroma = String(s.image.length === 3);
    figure.append(canvas, Object.assign(document.createElement('figcaption'), {textContent: s.name}));
    return figure;
  }));
}
