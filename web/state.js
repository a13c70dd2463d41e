// The page's state lives in the URL (after #), so a view can be shared by its address.
export const defaultState = () => ({
  models: [{id: 'log-normalized', params: {n: 50}}, {id: 'log', params: {n: 50}}, {id: 'schlick', params: {n: 50}}],
  theta: 55, phi: 135, phiV: 180, reference: 'phong-normalized', size: 256,
  slice: {theta_h: 30, theta_d: 30, phi_d: 90, exposure: 0, gamma: 2.2, chroma: false},
  estimator: '', samples: 4000, logPlot: false, timesCos: false, samplingSamples: 100000, channel: 'luminance',
  lit: {model: 0, obj: 'bundled', probe: 'bundled', estimator: 'mis', samples: 256, exposure: 0},
});

export function readState() {
  const hash = new URLSearchParams(location.hash.slice(1)).get('state');
  if (!hash) return defaultState();
  try {
    return {...defaultState(), ...JSON.parse(hash)};
  } catch {
    return defaultState();
  }
}

export function writeState(state) {
  history.replaceState(null, '', '#' + new URLSearchParams({state: JSON.stringify(state)}).toString());
}
