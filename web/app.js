// specula lab: model cards with parameter sliders, the spheres (WebGL2, the server's shaders),
// a difference view, plots, the half/difference slices (slices.js), the model editor, the fit panel and the designer panel. Every number comes from the
// server's API. A card holds a catalogue id or a definition of the editor's (sent as it is).
import {api, column} from './api.js';
import {readState, writeState, defaultState} from './state.js';
import {SphereView, drawDifference} from './spheres.js';
import {linePlot, polarPlot, palette} from './plots.js';
import {setupFit} from './fit.js';
import {setupDesign} from './design.js';
import {setupEditor} from './editor.js';
import {fetchSlices, drawSlices} from './slices.js';
import {drawSampling} from './sampling.js';
import {modelFile, settingsFile, readSettings} from './session.js';
import {renderLit, setupLit} from './lit.js';
import {LobeView} from './lobe3d.js';
import {drawCompensation} from './compensation.js';
import {channelApi, channelIndex, channelParams, hasRgb, kChannels} from './channels.js';

const $ = (id) => document.getElementById(id);
let catalogue = [], state = readState(), pending = null, generation = 0, edit = null, slices = null, litKey = '', lobe3d = null;
const views = [];

const info = (id) => catalogue.find((m) => m.id === id);
const defaultSlice = () => defaultState().slice;
// A card's model as the catalogue lists one: its own definition's, or the catalogue's entry.
const infoOf = (m) => m.definition
  ? {id: m.id, kind: m.definition.kind, params: Object.entries(m.definition.params).map(([name, p]) => ({name, ...p}))}
  : info(m.id);
const ref = (m) => m.definition ?? m.id;  // the model as a request names it
const isLobe = (m) => infoOf(m)?.kind === 'lobe';
const hasN = (m) => infoOf(m).params.some((p) => p.name === 'n');
const wide = (p) => p.max / Math.max(p.min, 1e-3) > 1000;  // log slider for n-like parameters
// The error plot's n: 1 to 1000, within the model's own range of n (a designed lobe's is its design range).
const errorRange = (m) => {
  const n = infoOf(m).params.find((p) => p.name === 'n');
  const lo = Math.max(1, n.min), hi = Math.min(1000, n.max);
  return lo < hi ? `${lo}:${hi}@25:log` : `${lo}`;
};

// Slider position in [0, 1000] ↔ parameter value.
function toSlider(p, v) {
  if (wide(p)) return 1000 * Math.log10(Math.max(v, 1)) / 4;  // n in [1, 10⁴]
  return 1000 * (v - p.min) / (p.max - p.min);
}
function fromSlider(p, s) {
  if (wide(p)) return Number((10 ** (4 * s / 1000)).toPrecision(3));
  return Number((p.min + (p.max - p.min) * s / 1000).toPrecision(3)) || (p.min_exclusive ? p.max / 1000 : p.min);
}

function modelCard(model, index) {
  const card = document.createElement('div');
  card.className = 'model';
  const header = document.createElement('header');
  const select = document.createElement('select');
  select.id = `model-${index}`;
  select.setAttribute('aria-label', `Model ${index + 1}`);
  const own = model.definition ? [new Option(`${model.id} (yours)`, model.id, false, true)] : [];
  select.replaceChildren(...own, ...catalogue.map((m) => new Option(m.id, m.id, false, !model.definition && m.id === model.id)));
  select.addEventListener('change', () => {
    state.models[index] = {id: select.value, params: {}};
    rebuild();
  });
  header.append(Object.assign(document.createElement('span'), {textContent: '●', style: `color:${palette[index]}`}), select);
  if (model.definition) {
    const button = Object.assign(document.createElement('button'), {type: 'button', textContent: 'Edit'});
    button.setAttribute('aria-label', `Edit model ${index + 1}`);
    button.addEventListener('click', () => edit(model.definition));
    header.append(button);
  }
  const visible = Object.assign(document.createElement('input'), {type: 'checkbox', id: `visible-${index}`, checked: !model.hidden});
  visible.addEventListener('change', () => { model.hidden = !visible.checked; schedule(); });
  const visibleLabel = Object.assign(document.createElement('label'), {htmlFor: visible.id, className: 'inline', textContent: 'shown'});
  visibleLabel.title = 'Shown in the plots and slices';
  const solo = Object.assign(document.createElement('button'), {type: 'button', textContent: 'Solo'});
  solo.setAttribute('aria-label', `Show model ${index + 1} alone in the plots`);
  solo.addEventListener('click', () => { state.models.forEach((m, i) => { m.hidden = i !== index; }); rebuild(); });
  header.append(visible, visibleLabel, solo);
  if (state.models.length > 1) {
    const remove = Object.assign(document.createElement('button'), {type: 'button', textContent: 'Remove'});
    remove.setAttribute('aria-label', `Remove model ${index + 1}`);
    remove.addEventListener('click', () => { state.models.splice(index, 1); rebuild(); });
    header.append(remove);
  }
  card.append(header);
  for (const p of infoOf(model).params) {
    const value = model.params[p.name] ?? p.default;
    const rgb = Array.isArray(value);
    const toggle = Object.assign(document.createElement('input'), {type: 'checkbox', id: `param-rgb-${index}-${p.name}`, checked: rgb});
    toggle.addEventListener('change', () => {
      const v = model.params[p.name] ?? p.default;
      model.params[p.name] = toggle.checked ? [v, v, v] : v[1];
      rebuild();
    });
    const toggleLabel = Object.assign(document.createElement('label'), {htmlFor: toggle.id, className: 'inline', textContent: `${p.name} per channel (R, G, B)`});
    if (rgb) kChannels.forEach((_, c) => card.append(...paramSlider(model, index, p, c)));
    else card.append(...paramSlider(model, index, p));
    card.append(toggle, toggleLabel);
  }
  return card;
}

/// A parameter's label and slider; with `channel` (0, 1, 2), one channel of an [R, G, B] value.
function paramSlider(model, index, p, channel) {
  const per = channel !== undefined, suffix = per ? `-${kChannels[channel]}` : '';
  const current = () => (per ? model.params[p.name][channel] : model.params[p.name] ?? p.default);
  const id = `param-${index}-${p.name}${suffix}`;
  const label = Object.assign(document.createElement('label'), {htmlFor: id});
  const output = Object.assign(document.createElement('output'), {textContent: current()});
  label.append(`${p.name}${per ? ` (${kChannels[channel].toUpperCase()})` : ''} = `, output);
  const slider = Object.assign(document.createElement('input'), {type: 'range', id, min: 0, max: 1000, step: 1});
  slider.value = toSlider(p, current());
  slider.addEventListener('input', () => {
    const v = fromSlider(p, Number(slider.value));
    if (per) model.params[p.name][channel] = v;
    else model.params[p.name] = v;
    output.textContent = v;
    schedule();
  });
  return [label, slider];
}

function rebuild() {
  $('models').replaceChildren(...state.models.map(modelCard));
  $('add-model').disabled = state.models.length >= 4;
  $('lit-model').replaceChildren(...state.models.map((m, i) => new Option(`${i + 1}: ${m.id}`, i, false, i === state.lit.model)));
  views.length = 0;
  $('spheres').replaceChildren(...state.models.map((m, i) => {
    const figure = document.createElement('figure');
    const canvas = Object.assign(document.createElement('canvas'), {id: `sphere-${i}`, width: state.size, height: state.size});
    canvas.setAttribute('aria-label', `Sphere shaded with ${m.id}`);
    views.push(new SphereView(canvas));
    canvas.addEventListener('pointerdown', (e) => {
      lightFromPointer(canvas, e);
      try { canvas.setPointerCapture(e.pointerId); } catch { /* a synthetic pointer has nothing to capture */ }
    });
    canvas.addEventListener('pointermove', (e) => { if (e.buttons & 1) lightFromPointer(canvas, e); });
    figure.append(canvas, Object.assign(document.createElement('figcaption'), {textContent: m.id}));
    return figure;
  }));
  views.reference = new SphereView(Object.assign(document.createElement('canvas'), {width: state.size, height: state.size}));
  schedule();
}

/// BRDF Explorer's lit sphere: the light comes from the direction of the sphere's point under the
/// pointer (x right, y up, z toward the viewer, the unit disc filling the canvas; outside it, its
/// edge), which sets θ_i and φ and so every view.
function lightFromPointer(canvas, event) {
  const box = canvas.getBoundingClientRect();
  let x = (2 * (event.clientX - box.left)) / box.width - 1, y = 1 - (2 * (event.clientY - box.top)) / box.height;
  const r = Math.hypot(x, y);
  if (r > 1) [x, y] = [x / r, y / r];
  const z = Math.sqrt(Math.max(0, 1 - x * x - y * y));
  state.theta = Math.min(89, Math.round((Math.acos(z) * 180) / Math.PI));
  state.phi = 5 * Math.round((Math.atan2(y, x) * 180) / Math.PI / 5);
  $('light-theta').value = state.theta;
  $('light-phi').value = state.phi;
  schedule();
}

function schedule() {
  clearTimeout(pending);
  pending = setTimeout(update, 60);
}

const lightDirection = () => {
  const t = (state.theta * Math.PI) / 180, p = (state.phi * Math.PI) / 180;
  return [Math.sin(t) * Math.cos(p), Math.sin(t) * Math.sin(p), Math.cos(t)];
};
const shaderRequest = (m) => ({model: ref(m), params: m.params, shader: true, light: lightDirection(), size: [state.size, state.size]});
const nextTask = () => new Promise((resolve) => setTimeout(resolve));

/// A request in the page's channel (channels.js): per channel where a parameter holds [R, G, B].
const capi = (path, body) => channelApi(path, body, state.channel);
/// The parameters a non-linear view (the sampler, the lit object) uses in the page's channel.
const viewParams = (m) => (hasRgb(m.params) ? channelParams(m.params, channelIndex(state.channel)) : m.params);
const lobeParams = (m) => Object.fromEntries(Object.entries(m.params).filter(([k]) => k !== 'n'));

async function drawSpheres(ticket) {
  const shaders = (m) => (hasRgb(m.params)
    ? Promise.all(kChannels.map((_, c) => api('/api/glsl', shaderRequest({...m, params: channelParams(m.params, c)}))))
    : api('/api/glsl', shaderRequest(m)));
  const answers = await Promise.all([...state.models, {id: state.reference, params: {}}].map(shaders));
  // One sphere per task (SwiftShader takes tens of ms each): input is handled between them.
  for (const [i, answer] of answers.entries()) {
    if (ticket !== generation) return;
    const view = i < state.models.length ? views[i] : views.reference;
    if (!view) return;  // the cards were rebuilt meanwhile
    if (Array.isArray(answer)) await view.drawChannels(answer, nextTask);
    else view.draw(answer);
    await nextTask();
  }
  const first = views[0].pixels();
  await nextTask();
  if (ticket !== generation) return;
  const max = drawDifference($('difference'), first, views.reference.pixels(), state.size, state.size);
  $('difference-caption').textContent = `|ΔL| of ${state.models[0].id} against ${state.reference}: max ${max.toPrecision(3)}`;
}

/// What the plot switches make of f (BRDF Explorer's): × N·L multiplies by the incident cosine
/// (a number, or one per point), log10(x + 1) compresses the range.
function shown(ys, cosines) {
  return ys.map((y, i) => {
    const v = state.timesCos ? y * (Array.isArray(cosines) ? cosines[i] : cosines) : y;
    return state.logPlot ? Math.log10(v + 1) : v;
  });
}

async function drawPlots(ticket) {
  const degrees = Array.from({length: 90}, (_, i) => i);
  const models = state.models.map((m, i) => ({...m, colour: palette[i], name: m.id})).filter((m) => !m.hidden);
  const lobe = await Promise.all(models.map(async (m) => isLobe(m)
    ? {...m, xs: degrees, ys: column(await capi('/api/eval', {model: ref(m), params: m.params, cos: degrees.map((d) => Math.cos((d * Math.PI) / 180))}), 'value')}
    : {...m, xs: degrees, ys: column(await capi('/api/eval', {model: ref(m), params: m.params, theta_i: state.theta, theta_o: degrees, phi_o: state.phiV}), 'value')}));
  const polar = await Promise.all(models.map(async (m) => {
    const at = (phi) => capi('/api/eval', {model: ref(m), params: m.params, theta_i: state.theta, theta_o: degrees, phi_o: phi});
    const [away, toward] = await Promise.all([at(180), at(0)]);
    return {...m, degrees: [...degrees.map((d) => d).reverse(), ...degrees.map((d) => -d)],
            values: [...column(away, 'value').reverse(), ...column(toward, 'value')]};
  }));
  const thetas = '0:85:5,89';
  const albedo = (await Promise.all(models.map(async (m) => {
    const t = await capi('/api/albedo', {model: ref(m), params: m.params, theta: thetas});
    const exact = {...m, xs: column(t, 'theta_deg'), ys: column(t, 'albedo')};
    if (!state.estimator) return [exact];
    const e = await capi('/api/albedo', {model: ref(m), params: m.params, theta: thetas, method: state.estimator, samples: state.samples});
    const band = (sign) => ({...m, dashed: true, xs: column(e, 'theta_deg'),
                             ys: e.rows.map((r) => r.albedo + sign * 2 * r.standard_error)});
    return [exact, band(-1), band(1)];
  }))).flat();
  // E(μ) of each model and, for a catalogue model, of M+ms (models/compensated.h), against μ.
  const energy = (await Promise.all(models.map(async (m) => {
    const curve = async (request, dashed) => {
      const t = await capi('/api/albedo', {model: request, params: m.params, theta: thetas});
      return {...m, dashed, xs: column(t, 'theta_deg').map((d) => Math.cos((d * Math.PI) / 180)), ys: column(t, 'albedo')};
    };
    return m.definition ? [await curve(ref(m), false)] : Promise.all([curve(m.id, false), curve(`${m.id}+ms`, true)]);
  }))).flat();
  const error = isLobe({id: state.reference}) ? await Promise.all(models.filter((m) => isLobe(m) && hasN(m)).map(async (m) => {
    const t = await capi('/api/error', {model: ref(m), params: lobeParams(m), reference: state.reference, n: errorRange(m)});
    return {...m, xs: column(t, 'n'), ys: column(t, 'max_abs')};
  })) : [];
  const coefficients = await Promise.all(models.filter((m) => isLobe(m) && hasN(m)).map(async (m) => {
    const used = await capi('/api/eval', {model: ref(m), params: m.params, cos: [1]});
    const logLobe = !m.definition && m.id.startsWith('log');  // the paper fitted k(n) for the log lobe only
    const exact = await capi('/api/normalize', {model: ref(m), params: lobeParams(m), n: [m.params.n ?? infoOf(m).params[0].default],
                                               ...(logLobe ? {compare: 'log-paper'} : {})});
    return [m.id, Number(used.coef), column(exact, 'coef')[0], logLobe ? column(exact, 'coef_compare')[0] : '-'];
  }));
  // A coarse check (fewer pairs, a 5° grid) keeps each update quick.
  const checks = await Promise.all(models.map(async (m) => [m.id, (await capi('/api/check', {model: ref(m), params: m.params, pairs: 1000, step: 5}))[0]]));
  if (ticket !== generation) return;
  const cosI = Math.cos((state.theta * Math.PI) / 180);
  const label = (y) => (state.logPlot ? `log10(${y}${state.timesCos ? ' · N·L' : ''} + 1)` : `${y}${state.timesCos ? ' · N·L' : ''}`);
  linePlot($('plot-lobe'), lobe.map((s) => ({...s, ys: isLobe(s) ? shown(s.ys, 1) : shown(s.ys, cosI)})), {xLabel: 'angle (degrees)', yLabel: label('k·F or f')});
  polarPlot($('plot-polar'), polar.map((s) => ({...s, values: shown(s.values, cosI)})), {lightDeg: state.theta});
  linePlot($('plot-albedo'), albedo, {xLabel: 'θi (degrees)', yLabel: 'albedo ρ'});
  linePlot($('plot-energy'), energy, {xLabel: 'μ = cos θi', yLabel: 'E(μ)'});
  linePlot($('plot-error'), error, {xLabel: 'n', yLabel: 'max |F − Fref|', logX: true});
  document.querySelector('#checks tbody').replaceChildren(...checks.map(([id, c]) => tableRow(
    [id, c.albedo_normal, c.max_albedo, c.conserves_energy ? 'yes' : 'no', c.reciprocal ? 'yes' : 'no', c.non_negative ? 'yes' : 'no'])));
  document.querySelector('#coefficients tbody').replaceChildren(...coefficients.map(tableRow));
}

/// BRDF Explorer's 3-D lobe: f over the outgoing hemisphere (/api/hemisphere), turned to the
/// light's azimuth, through the plot switches.
async function drawLobe3d(ticket) {
  const models = state.models.map((m, i) => ({...m, colour: palette[i]})).filter((m) => !m.hidden);
  const grids = await Promise.all(models.map((m) => capi('/api/hemisphere', {model: ref(m), params: m.params, theta_i: state.theta})));
  if (ticket !== generation) return;
  const cosI = Math.cos((state.theta * Math.PI) / 180);
  lobe3d.setData(grids.map((g, i) => ({colour: models[i].colour, thetaDeg: g.theta_o_deg, phiDeg: g.phi_o_deg.map((p) => p + state.phi),
                                        values: g.values.map((row) => shown(row.map((v) => v ?? 0), cosI))})), lightDirection());
}

async function drawSliceViews(ticket) {
  const models = state.models.map((m, i) => ({request: ref(m), params: m.params, name: m.id, colour: palette[i], hidden: m.hidden,
                                              channelParams: hasRgb(m.params) ? kChannels.map((_, c) => channelParams(m.params, c)) : null}))
    .filter((m) => !m.hidden);
  const fetched = await fetchSlices(models, state.slice, capi);
  if (ticket !== generation) return;
  slices = fetched;
  drawSlices(slices, state.slice, shown);
}

/// The slices' sliders: the angles ask the server again; exposure and gamma redraw what it gave.
function setupSliceControls() {
  $('slice-chroma').checked = Boolean(state.slice.chroma);
  $('slice-chroma').addEventListener('change', () => { state.slice.chroma = $('slice-chroma').checked; schedule(); });
  for (const key of ['theta_h', 'theta_d', 'phi_d', 'exposure', 'gamma']) {
    const id = `slice-${key.replace('_', '-')}`, input = $(id), output = $(`${id}-value`);
    input.value = state.slice[key];
    output.textContent = state.slice[key];
    input.addEventListener('input', () => {
      state.slice[key] = Number(input.value);
      output.textContent = state.slice[key];
      if ((key === 'exposure' || key === 'gamma') && slices) {
        writeState(state);
        drawSlices(slices, state.slice, shown);
      } else {
        schedule();
      }
    });
  }
}

/// The lit object's render restarts only when what it shows changes (not on a light move).
function drawLit() {
  const index = Math.min(state.lit.model, state.models.length - 1), m = state.models[index];
  const key = JSON.stringify([ref(m), viewParams(m), state.lit]);
  if (key === litKey) return;
  litKey = key;
  renderLit({request: ref(m), params: viewParams(m), name: m.id}, state.lit, showError);
}

function showError(e) {
  $('status').textContent = e.message;
  $('status').className = 'error';
}

function tableRow(cells) {
  const row = document.createElement('tr');
  for (const c of cells) row.append(Object.assign(document.createElement('td'), {textContent: typeof c === 'number' ? c.toPrecision(8) : c}));
  return row;
}

/// The editor's definition as a card: the card of the same id is updated, else one is added
/// (the last replaced when there are four); its parameters start at their defaults.
function applyDefinition(definition) {
  const card = {id: definition.id, definition, params: {}};
  const same = state.models.findIndex((m) => m.id === definition.id);
  if (same >= 0) state.models[same] = card;
  else if (state.models.length < 4) state.models.push(card);
  else state.models[3] = card;
  rebuild();
}

async function update() {
  const ticket = ++generation;
  $('light-theta-value').textContent = state.theta;
  $('plot-phi-v-value').textContent = state.phiV;
  $('light-phi-value').textContent = state.phi;
  writeState(state);
  $('status').textContent = 'computing…';
  $('status').className = '';
  try {
    const first = state.models[0];
    drawLit();
    const shownModels = state.models.filter((m) => !m.hidden && !m.definition).map((m) => ({request: ref(m), params: viewParams(m), name: m.id}));
    await Promise.all([drawSpheres(ticket), drawPlots(ticket), drawSliceViews(ticket), drawLobe3d(ticket),
                       drawCompensation(shownModels, $('plot-compensation'), $('compensation-caption'), () => ticket === generation),
                       drawSampling({request: ref(first), params: viewParams(first), name: first.id}, state.theta, state.samplingSamples)]);
    if (ticket !== generation) return;
    $('status').textContent = 'ready';
    document.body.dataset.renders = String(Number(document.body.dataset.renders || 0) + 1);
  } catch (e) {
    $('status').textContent = e.message;
    $('status').className = 'error';
  }
}

async function main() {
  catalogue = await api('/api/models');
  state.models = state.models.filter((m) => m.definition || info(m.id)).slice(0, 4);
  if (!state.models.length) state.models = [{id: 'log-normalized', params: {n: 50}}];
  $('reference').replaceChildren(...catalogue.map((m) => new Option(m.id, m.id, false, m.id === state.reference)));
  $('reference').addEventListener('change', () => { state.reference = $('reference').value; schedule(); });
  for (const [id, key] of [['light-theta', 'theta'], ['light-phi', 'phi'], ['plot-phi-v', 'phiV']]) {
    $(id).value = state[key];
    $(id).addEventListener('input', () => { state[key] = Number($(id).value); schedule(); });
  }
  $('add-model').addEventListener('click', () => {
    if (state.models.length < 4) state.models.push({id: 'phong-normalized', params: {n: 50}});
    rebuild();
  });
  state.slice = {...defaultSlice(), ...state.slice};
  for (const [id, key] of [['plot-log', 'logPlot'], ['plot-times-cos', 'timesCos']]) {
    $(id).checked = Boolean(state[key]);
    $(id).addEventListener('change', () => { state[key] = $(id).checked; schedule(); });
  }
  $('channel').value = state.channel;
  $('channel').addEventListener('change', () => { state.channel = $('channel').value; schedule(); });
  $('session-save').addEventListener('click', () => {
    const link = (name, text, type) => {
      const a = Object.assign(document.createElement('a'), {href: URL.createObjectURL(new Blob([text], {type})), download: name, textContent: name});
      a.id = `session-${name.split('.').pop()}`;
      return a;
    };
    $('session-links').replaceChildren(link('specula-session.toml', modelFile(state), 'application/toml'), ' ',
                                       link('specula-session.json', settingsFile(state), 'application/json'));
  });
  $('session-load').addEventListener('change', async () => {
    try {
      const loaded = readSettings(await $('session-load').files[0].text());
      writeState({...defaultState(), ...loaded});
      location.reload();
    } catch (e) {
      $('status').textContent = e.message;
      $('status').className = 'error';
    }
  });
  $('sampling-samples').value = String(state.samplingSamples);
  $('sampling-samples').addEventListener('change', () => { state.samplingSamples = Number($('sampling-samples').value); schedule(); });
  $('albedo-estimator').value = state.estimator;
  $('albedo-samples').value = state.samples;
  $('albedo-estimator').addEventListener('change', () => { state.estimator = $('albedo-estimator').value; schedule(); });
  $('albedo-samples').addEventListener('change', () => {
    state.samples = Math.min(100000, Math.max(100, Math.round(Number($('albedo-samples').value) || 4000)));
    $('albedo-samples').value = state.samples;
    schedule();
  });
  setupSliceControls();
  lobe3d = new LobeView($('lobe3d'));
  state.lit = {...defaultState().lit, ...state.lit};
  setupLit(state.lit, schedule, showError);
  $('lit-model').addEventListener('change', () => { state.lit.model = Number($('lit-model').value); schedule(); });
  setupFit(catalogue.filter((m) => m.kind === 'lobe'));
  setupDesign(catalogue.filter((m) => m.kind === 'lobe'), applyDefinition);
  edit = setupEditor(applyDefinition);
  rebuild();
}

main().catch((e) => { $('status').textContent = e.message; $('status').className = 'error'; });
