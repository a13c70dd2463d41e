// BRDF Explorer's lit object under an environment: a model on a mesh (the unit sphere, the bundled
// knot, or an uploaded OBJ) lit by a latitude-longitude probe (the white furnace, the bundled sky,
// or an uploaded EXR/PNG), with the estimator chosen. The server's CPU renderer refines the image
// pass after pass in its job queue (POST /api/environment); the page polls it and shows each frame
// with its sample count, so the page itself does no heavy work (docs/serve.md says why).
import {api, del, pollJob} from './api.js';

const $ = (id) => document.getElementById(id);
let job = null, stopPolling = () => {};

/// Sends a file's bytes to /api/upload/KIND; the answer's id, or an Error with the server's message.
async function upload(kind, file) {
  const response = await fetch(`/api/upload/${kind}`, {method: 'POST', body: await file.arrayBuffer()});
  const answer = await response.json();
  if (!response.ok) throw new Error(`${file.name}: ${answer.error}`);
  return answer;
}

function cancel() {
  stopPolling();
  if (job) del(`/api/environment/${job}`).catch(() => {});
  job = null;
}

function show(status) {
  const frame = $('lit-image');
  if (status.png) frame.src = `data:image/png;base64,${status.png}`;
  $('lit-counter').textContent = `${status.samples} of ${status.target} samples per pixel · ${status.seconds.toFixed(1)} s · ${status.state}`;
  frame.dataset.samples = String(status.samples);
  frame.dataset.state = status.state;
}

/// Starts a render of `model` ({request, params, name}) with the view's settings, cancelling the last.
export async function renderLit(model, settings, onError) {
  cancel();
  $('lit-image').dataset.state = 'starting';
  $('lit-caption').textContent = `${model.name} on the ${settings.obj === 'sphere' ? 'sphere' : settings.obj === 'bundled' ? 'knot' : 'uploaded mesh'} under ${settings.probe === 'furnace' ? 'the white furnace' : settings.probe === 'bundled' ? 'the sky' : 'the uploaded probe'}, ${settings.estimator} estimator`;
  try {
    const started = await api('/api/environment', {model: model.request, params: model.params, obj: settings.obj, probe: settings.probe,
                                                   estimator: settings.estimator, samples: settings.samples, size: [160, 160],
                                                   exposure: settings.exposure});
    job = started.job;
    stopPolling = pollJob(started.url, 250, show, (e) => { if (e) onError(e); });
  } catch (e) {
    onError(e);
  }
}

/// The view's controls: mesh, probe, estimator, samples, exposure and the two uploads. `changed`
/// re-renders; `settings` is the page state's `lit` part, kept up to date here.
export function setupLit(settings, changed, onError) {
  for (const key of ['obj', 'probe', 'estimator', 'samples', 'exposure']) {
    const input = $(`lit-${key}`);
    if (![...(input.options ?? [])].some((o) => o.value === String(settings[key])) && input.tagName === 'SELECT')
      input.append(new Option(`upload ${settings[key]}`, settings[key]));
    input.value = String(settings[key]);
    input.addEventListener('change', () => {
      settings[key] = key === 'samples' || key === 'exposure' ? Number(input.value) : input.value;
      changed();
    });
  }
  for (const [kind, key] of [['obj', 'obj'], ['probe', 'probe']]) {
    $(`lit-upload-${kind}`).addEventListener('change', async (event) => {
      const file = event.target.files[0];
      if (!file) return;
      try {
        const answer = await upload(kind, file);
        const id = answer[kind];
        $(`lit-${key}`).append(new Option(`${file.name} (${id})`, id));
        $(`lit-${key}`).value = id;
        settings[key] = id;
        changed();
      } catch (e) {
        onError(e);
      }
    });
  }
}
