// The model editor: a formula — a lobe in c, a lobe in u = −ln c, or a BRDF in nl, nv, nh, vh,
// lv — with its form, normalization and parameters, sent as a definition object with a model
// file's keys (docs/models.md). Apply — or a pause in typing — has the server check it (POST
// /api/glsl builds its shader) and then adds or updates its model card; the server's error, the
// key at fault and why, shows next to the formula.
import {api} from './api.js';

const $ = (id) => document.getElementById(id);
const defaultParams = () => [{name: 'n', default: 20, min: 0, min_exclusive: true, max: 1e6}];

function cellInput(row, index, key, param, onChange) {
  const input = Object.assign(document.createElement('input'), {id: `editor-param-${index}-${key}`, size: 6});
  input.setAttribute('aria-label', `parameter ${index + 1} ${key}`);
  if (key === 'min_exclusive') Object.assign(input, {type: 'checkbox', checked: param.min_exclusive});
  else input.value = param[key];
  input.addEventListener('change', () => onChange(key === 'min_exclusive' ? input.checked : input.value));
  const cell = document.createElement('td');
  cell.append(input);
  row.append(cell);
}

/// Sets up the editor's form; `onApply(definition)` gets each definition the server accepted.
/// Returns edit(definition), which loads a definition into the form.
export function setupEditor(onApply) {
  let params = defaultParams();

  const renderParams = () => {
    document.querySelector('#editor-params tbody').replaceChildren(...params.map((p, i) => {
      const row = document.createElement('tr');
      for (const key of ['name', 'default', 'min', 'max', 'min_exclusive']) cellInput(row, i, key, p, (v) => { p[key] = v; });
      const remove = Object.assign(document.createElement('button'), {type: 'button', textContent: '×'});
      remove.setAttribute('aria-label', `Remove parameter ${i + 1}`);
      remove.addEventListener('click', () => { params.splice(i, 1); renderParams(); });
      const cell = document.createElement('td');
      cell.append(remove);
      row.append(cell);
      return row;
    }));
  };

  const isLobe = () => $('editor-kind').value !== 'brdf';
  const showKind = () => { for (const id of ['editor-form', 'editor-normalization']) $(id).disabled = !isLobe(); };

  // Numbers as typed: a blank or malformed one is sent as null, which the server reports as missing.
  const definition = () => {
    const d = {id: $('editor-id').value.trim() || 'user', name: 'user-defined model', kind: isLobe() ? 'lobe' : 'brdf',
               [$('editor-kind').value]: $('editor-formula').value,
               params: Object.fromEntries(params.map((p) => [p.name.trim(), {default: Number(p.default), min: Number(p.min),
                                                                             max: Number(p.max), min_exclusive: Boolean(p.min_exclusive)}]))};
    if (isLobe()) Object.assign(d, {form: $('editor-form').value, normalization: $('editor-normalization').value.trim()});
    return d;
  };

  const showError = (e) => {
    $('editor-error').textContent = e ? (e.field ? `${e.field}: ${e.reason}` : e.message) : '';
    $('editor-formula').setAttribute('aria-invalid', String(Boolean(e)));
  };

  // Apply on submit, and while typing once the edits pause: only the latest answer counts, so a
  // slow answer to an earlier keystroke never overwrites a later one.
  let latest = 0, pause = 0;
  const apply = async () => {
    const d = definition(), request = ++latest;
    try {
      await api('/api/glsl', {model: d});
      if (request !== latest) return;
      showError(null);
      onApply(d);
    } catch (e) {
      if (request === latest) showError(e);
    }
  };
  $('editor').addEventListener('submit', (event) => {
    event.preventDefault();
    clearTimeout(pause);
    apply();
  });
  $('editor').addEventListener('input', () => {
    clearTimeout(pause);
    pause = setTimeout(apply, 600);
  });
  $('editor-kind').addEventListener('change', showKind);
  $('editor-add-param').addEventListener('click', () => {
    params.push({name: `p${params.length + 1}`, default: 1, min: 0, min_exclusive: false, max: 10});
    renderParams();
  });
  renderParams();
  showKind();

  return (d) => {
    const kind = ['lobe', 'lobe_u', 'brdf'].find((key) => d[key] !== undefined);
    $('editor-id').value = d.id;
    $('editor-kind').value = kind;
    $('editor-formula').value = d[kind];
    if (d.form) $('editor-form').value = d.form;
    if (d.normalization) $('editor-normalization').value = d.normalization;
    params = Object.entries(d.params).map(([name, p]) => ({name, ...p}));
    renderParams();
    showKind();
    showError(null);
  };
}
