// The server's JSON API: GET without a body, POST with one (again while the server says it is
// busy); an error answer throws
// an Error whose message names the field ("n: …"), with the field and the reason apart too.
// A busy server (every computing place taken: 503 with Retry-After) is asked again after the
// seconds it names, a few times: the page sends several requests per view at once.
const kRetries = 8;

export async function api(path, body) {
  const init = body === undefined ? {} : {method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(body)};
  let response = await fetch(path, init);
  for (let retry = 0; retry < kRetries && response.status === 503 && response.headers.has('Retry-After'); ++retry) {
    await new Promise((resolve) => setTimeout(resolve, 1000 * Number(response.headers.get('Retry-After') || 1)));
    response = await fetch(path, init);
  }
  const answer = await response.json();
  if (!response.ok)
    throw Object.assign(new Error(answer.field ? `${answer.field}: ${answer.error}` : answer.error), {field: answer.field, reason: answer.error});
  return answer;
}

export const del = async (path) => (await fetch(path, {method: 'DELETE'})).json();

/// The rows of a table answer as arrays per column: column(table, 'value').
export const column = (table, name) => table.rows.map((row) => row[name]);

/// Polls the job at `path` every `ms` until it leaves "running": show(status) on each answer, then
/// ended() (ended(error) when a poll fails). Returns a function that stops the polling.
export function pollJob(path, ms, show, ended) {
  const timer = setInterval(async () => {
    try {
      const status = await api(path);
      show(status);
      if (status.state !== 'running') {
        clearInterval(timer);
        ended();
      }
    } catch (e) {
      clearInterval(timer);
      ended(e);
    }
  }, ms);
  return () => clearInterval(timer);
}
