// Saved sessions (BRDF Explorer's .bparam): the page's own models as a model file any command
// reads (`specula --models specula-session.toml …`, docs/models.md) and the page's state as a
// small settings file, which loads the page back as it was (the URL holds the same state).

const quoted = (text) => JSON.stringify(String(text));  // a TOML basic string is a JSON string
const value = (v) => (typeof v === 'string' ? quoted(v) : typeof v === 'boolean' ? String(v)
  : Array.isArray(v) ? `[${v.map(value).join(', ')}]` : String(v));

/// One definition object (the editor's, or a designed lobe's) as a [[model]] table.
function modelTable(definition) {
  const lines = ['[[model]]'];
  for (const [key, v] of Object.entries(definition))
    if (key !== 'params' && v !== undefined && v !== null) lines.push(`${key} = ${value(v)}`);
  for (const [name, p] of Object.entries(definition.params ?? {})) {
    lines.push(`[model.params.${name}]`);
    for (const [key, v] of Object.entries(p)) if (v !== undefined && v !== null) lines.push(`${key} = ${value(v)}`);
  }
  return lines.join('\n');
}

/// The model file of the page's own models (none: `model = []`, a file that adds none).
export function modelFile(state) {
  const own = state.models.filter((m) => m.definition).map((m) => modelTable(m.definition));
  return `# specula lab session: the page's own models (load with specula --models FILE)\n` +
    (own.length ? own.join('\n\n') : 'model = []') + '\n';
}

/// The settings file: the page's whole state, its own models' definitions included.
export const settingsFile = (state) => JSON.stringify({specula_session: 1, ...state}, null, 1) + '\n';

/// The state a settings file holds; throws an Error naming what is wrong.
export function readSettings(text) {
  let parsed;
  try { parsed = JSON.parse(text); } catch { throw new Error('session: not a JSON settings file'); }
  if (!parsed || parsed.specula_session !== 1 || !Array.isArray(parsed.models) || !parsed.models.length)
    throw new Error('session: not a specula settings file (no specula_session: 1 or no models)');
  delete parsed.specula_session;
  return parsed;
}
