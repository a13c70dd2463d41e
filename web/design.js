// The designer panel: POST /api/design for cheap lobes against a target over a range of its
// parameter, poll GET /api/design/{id} while the front grows (finished lobes first on the cost
// model's axis, then timed and checked), DELETE to cancel; "Add" puts a member on the page as a
// model card (its definition object, normalized by quadrature), and so does a click on its point
// of the front's chart (error against cost; the references grey, where they are timed).
import {api, del, pollJob} from './api.js';
import {paretoPlot} from './plots.js';

const cell = (text) => Object.assign(document.createElement('td'), {textContent: text});
const number = (x, digits = 4) => (x === null || x === undefined ? '-' : Number(x).toPrecision(digits));

export function setupDesign(lobeModels, addModel) {
  const $ = (id) => document.getElementById(id);
  const status = $('design-status'), body = document.querySelector('#design-front tbody');
  // Besides lobes, the engine terms (functions of c = cos θ, docs/designer.md): the server gives
  // their own parameter and range, so the page's are not sent for them.
  const terms = Object.assign(document.createElement('optgroup'), {label: 'engine terms (functions, GET /api/terms)'});
  api('/api/terms').then((list) => terms.append(...list.map((t) => Object.assign(new Option(t.id, t.id), {title: t.summary}))));
  const lobes = Object.assign(document.createElement('optgroup'), {label: 'lobes'});
  lobes.append(...lobeModels.map((m) => new Option(m.id, m.id, m.id === 'phong', m.id === 'phong')));
  $('design-target').replaceChildren(lobes, terms);
  const isTerm = () => $('design-target').selectedOptions[0]?.parentElement === terms;
  $('design-target').addEventListener('change', () => {
    for (const id of ['design-param', 'design-lo', 'design-hi']) $(id).disabled = isTerm();
  });
  let job = null, stopPolling = () => {};

  const memberRow = (l) => {
    const row = document.createElement('tr');
    row.className = l.kind;
    for (const text of [l.id, number(l.max_abs_error), number(l.ns_per_eval, 3), l.ops ?? l.model_cost ?? '-',
                        l.kind === 'reference' ? '-' : (l.check || '…'), l.display])
      row.append(cell(text));
    const actions = document.createElement('td');
    if (l.definition) {
      const add = Object.assign(document.createElement('button'), {type: 'button', textContent: 'Add'});
      add.setAttribute('aria-label', `Add ${l.id} to the page's models`);
      add.addEventListener('click', () => addModel(l.definition_normalized));
      actions.append(add);
    }
    row.append(actions);
    return row;
  };

  const show = (s) => {
    status.className = s.state === 'failed' ? 'error' : '';
    status.textContent = `job ${s.job}: ${s.state} · ${s.phase} ${s.done}/${s.total} · ${s.forms_screened} shapes screened` +
      ` · ${s.elapsed_s.toFixed(1)} s` + (s.final ? '' : ' · front so far on the cost model') + (s.error ? ` · ${s.error}` : '');
    body.replaceChildren(...s.front.map(memberRow), ...s.references.map(memberRow), ...(s.refused ?? []).map(memberRow));
    const timed = [...s.front, ...s.references].some((l) => l.ns_per_eval !== null && l.ns_per_eval !== undefined);
    const cost = (l) => (timed ? l.ns_per_eval : l.model_cost) ?? NaN;  // untimed references have no cost
    paretoPlot($('design-chart'), [...s.front, ...s.references].map((l) => ({
      x: cost(l), y: Number(l.max_abs_error), reference: l.kind === 'reference',
      label: `${l.id}: max error ${number(l.max_abs_error)}, cost ${number(cost(l), 3)}${l.definition ? ' (add it to the page)' : ''}`,
      onPick: l.definition ? () => addModel(l.definition_normalized) : undefined})),
      {xLabel: timed ? 'ns per value' : 'cost model', yLabel: 'max |F − target|'});
  };

  const finish = (error) => {
    stopPolling();
    $('design-start').disabled = false;
    $('design-cancel').disabled = true;
    if (error) status.textContent = error.message;
  };

  $('design-form').addEventListener('submit', async (event) => {
    event.preventDefault();
    try {
      const request = {target: $('design-target').value, ops: $('design-ops').value.trim(),
                       max_cost: Number($('design-cost').value), time: Number($('design-time').value),
                       timing: $('design-timing').checked,
                       ...(isTerm() ? {} : {param: $('design-param').value.trim(), range: [Number($('design-lo').value), Number($('design-hi').value)]})};
      job = (await api('/api/design', request)).job;
      $('design-start').disabled = true;
      $('design-cancel').disabled = false;
      body.replaceChildren();
      status.className = '';
      status.textContent = `job ${job} started`;
      stopPolling = pollJob(`/api/design/${job}`, 500, show, finish);
    } catch (e) {
      status.textContent = e.message;
      status.className = 'error';
    }
  });

  $('design-cancel').addEventListener('click', async () => {
    if (job === null) return;
    const s = await del(`/api/design/${job}`);
    if (s.front) show(s);
    finish();
  });
}
