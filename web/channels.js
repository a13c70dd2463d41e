// BRDF Explorer's channel choice: a model's parameter may hold one value per colour channel,
// [R, G, B] (a metal's η and κ, a tinted F0), and every view shows the channel the page picks: R, G,
// B, or the luminance, 0.2126 R + 0.7152 G + 0.0722 B (Rec. 709). The server computes one channel
// at a time; f and the albedo are linear in it, so the luminance of a view's numbers is that sum of
// the three channels' answers.
import {api} from './api.js';

export const kChannels = ['r', 'g', 'b'];
const kLuminance = [0.2126, 0.7152, 0.0722];

export const hasRgb = (params) => Object.values(params ?? {}).some(Array.isArray);

/// The parameters of channel c (0, 1, 2): an [R, G, B] value's c-th, others as they are.
export const channelParams = (params, c) =>
  Object.fromEntries(Object.entries(params).map(([k, v]) => [k, Array.isArray(v) ? v[c] : v]));

/// The channel whose parameters a non-linear view (the sampler, the lit object) uses: the luminance's
/// largest weight, green, stands for it.
export const channelIndex = (channel) => Math.max(0, kChannels.indexOf(channel === 'luminance' ? 'g' : channel));

/// The weighted sum of answers of one shape: numbers summed with the weights, anything else the first's.
function combine(answers, weights) {
  const [first] = answers;
  if (typeof first === 'number') return answers.reduce((sum, a, i) => sum + weights[i] * a, 0);
  if (Array.isArray(first)) return first.map((_, k) => combine(answers.map((a) => a[k]), weights));
  if (first && typeof first === 'object')
    return Object.fromEntries(Object.keys(first).map((k) => [k, combine(answers.map((a) => a[k]), weights)]));
  return first;
}

/// api() for a view that is linear in the channel: a body whose params hold [R, G, B] values is
/// asked per channel, its luminance the weighted sum of the three answers.
export async function channelApi(path, body, channel) {
  if (!hasRgb(body.params)) return api(path, body);
  if (channel !== 'luminance') return api(path, {...body, params: channelParams(body.params, kChannels.indexOf(channel))});
  const answers = await Promise.all(kChannels.map((_, c) => api(path, {...body, params: channelParams(body.params, c)})));
  return combine(answers, kLuminance);
}
