-- wrk script: POST the JSON body in the environment variable BODY to wrk's URL; at the end, print
-- the socket errors, the answers that are not 2xx/3xx (summary.errors.status: a 400 counts) and
-- the latency percentiles.
wrk.method = "POST"
wrk.body = os.getenv("BODY")
wrk.headers["Content-Type"] = "application/json"

function done(summary, latency, requests)
  io.write(string.format("  requests: %d, socket errors: %d connect / %d read / %d write / %d timeout, non-2xx: %d\n",
    summary.requests, summary.errors.connect, summary.errors.read, summary.errors.write,
    summary.errors.timeout, summary.errors.status))
  io.write("  latency percentiles (ms):")
  for _, p in ipairs({50, 90, 99, 99.9}) do
    io.write(string.format("  p%g %.3f", p, latency:percentile(p) / 1000))
  end
  io.write(string.format("  max %.3f\n", latency.max / 1000))
end
