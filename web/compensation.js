// The energy view's second half (issue 39's question, on the page): for a GGX model with its
// Fresnel, each published energy compensation's directional albedo minus the random walk's on the
// same microsurface (the truth: single + multiple scattering), against μ = cos θ, with the walk's
// ± 2 standard errors dashed. Every number is the server's (/api/compensation).
import {api, column} from './api.js';
import {linePlot} from './plots.js';

const kColours = ['#7f7f7f', '#d62728', '#ff7f0e', '#bcbd22', '#8c564b', '#9467bd', '#17becf', '#1f77b4'];
const answers = new Map();  // the walk does not depend on the light: asked once per model and parameters

function measured(model) {
  const key = JSON.stringify([model.request, model.params]);
  if (!answers.has(key)) answers.set(key, api('/api/compensation', {model: model.request, params: model.params}).catch((e) => {
    answers.delete(key);
    throw e;
  }));
  return answers.get(key);
}

/// The first catalogue model of `models` ({request, params, name}) the walk applies to, plotted into
/// `container`; the caption says which model (or that none applies, or why it could not be
/// measured: an error here never stops the page's other views).
export async function drawCompensation(models, container, caption, isCurrent) {
  const model = models.find((m) => /^ggx(-[a-z0-9]+)?(\+ms)?$/.test(m.name));
  if (!model) {
    container.replaceChildren();
    caption.textContent = 'no GGX model on the page: the random walk is GGX\'s';
    return;
  }
  let t;
  try {
    t = await measured(model);
  } catch (e) {  // the walk past the server's deadline (a loaded machine): said here, the other views go on
    if (isCurrent()) caption.textContent = `${model.name}: the compensations could not be measured: ${e.message}`;
    return;
  }
  if (!isCurrent()) return;
  const mu = column(t, 'mu'), truth = t.rows.map((r) => r.E_F + r.E_ms);
  const names = t.compensations.split(',');
  const error = (name) => t.rows.map((r, i) => r[`albedo_${name}`] - truth[i]);
  const band = (sign) => t.rows.map((r) => sign * 2 * Math.hypot(r.E_F_se, r.E_ms_se));
  linePlot(container, [...names.map((name, i) => ({name, colour: kColours[i], xs: mu, ys: error(name)})),
                       {name: 'walk ± 2σ', colour: '#000', dashed: true, xs: mu, ys: band(1)},
                       {name: 'walk − 2σ', colour: '#000', dashed: true, xs: mu, ys: band(-1)}],
           {xLabel: 'μ = cos θi', yLabel: 'albedo − walk'});
  const worst = names.map((name) => [name, Math.max(...error(name).map(Math.abs))]);
  caption.textContent = `${model.name}: largest |albedo − walk| ` + worst.map(([n, e]) => `${n} ${e.toPrecision(2)}`).join(', ');
  container.dataset.model = model.name;
}
