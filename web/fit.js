// The fit panel: POST /api/fit for a lobe model's normalization k(n), poll GET /api/fit/{id}
// while the Pareto front grows, DELETE to cancel; each formula copies as C++ or GLSL.
import {api, del, pollJob} from './api.js';

export function setupFit(lobeModels) {
  const $ = (id) => document.getElementById(id);
  const select = $('fit-model'), status = $('fit-status'), body = document.querySelector('#fit-front tbody');
  select.replaceChildren(...lobeModels.map((m) => new Option(m.id, m.id, m.id === 'log', m.id === 'log')));
  let job = null, stopPolling = () => {};

  const copyButton = (label, text) => {
    const button = document.createElement('button');
    button.type = 'button';
    button.textContent = label;
    button.addEventListener('click', async () => {
      try { await navigator.clipboard.writeText(text); button.textContent = `${label} ✓`; } catch { window.prompt(`${label}:`, text); }
    });
    return button;
  };

  const show = (s) => {
    status.textContent = `job ${s.job}: ${s.state}` + (s.stopped_by ? ` (stopped by ${s.stopped_by})` : '') +
      ` · ${s.evaluations} evaluations · ${s.generations} generations · ${s.elapsed_s.toFixed(1)} s` +
      (s.snap ? ' · constants snapped' : ' · constants as fitted');
    body.replaceChildren(...s.front.map((c, i) => {
      const row = document.createElement('tr');
      if (i === s.chosen) row.className = 'chosen';
      for (const text of [c.size, c.train_error === null ? '-' : c.train_error.toPrecision(6), c.display + (i === s.chosen ? '  ← chosen' : '')])
        row.append(Object.assign(document.createElement('td'), {textContent: text}));
      const cell = document.createElement('td');
      cell.append(copyButton('C++', c.cpp), ' ', copyButton('GLSL', c.glsl));
      row.append(cell);
      return row;
    }));
  };

  const finish = (error) => {
    stopPolling();
    $('fit-start').disabled = false;
    $('fit-cancel').disabled = true;
    if (error) status.textContent = error.message;
  };

  $('fit-form').addEventListener('submit', async (event) => {
    event.preventDefault();
    try {
      const request = {model: select.value, n: $('fit-n').value, generations: Number($('fit-generations').value), time: 60,
                       snap: $('fit-snap').checked};
      if ($('fit-round').value !== '') request.round = Number($('fit-round').value);
      job = (await api('/api/fit', request)).job;
      $('fit-start').disabled = true;
      $('fit-cancel').disabled = false;
      body.replaceChildren();
      status.textContent = `job ${job} started`;
      stopPolling = pollJob(`/api/fit/${job}`, 400, show, finish);
    } catch (e) {
      status.textContent = e.message;
      status.className = 'error';
    }
  });

  $('fit-cancel').addEventListener('click', async () => {
    if (job === null) return;
    const s = await del(`/api/fit/${job}`);
    if (s.front) show(s);
    finish();
  });
}
