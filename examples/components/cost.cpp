// specula::cost: the lobe benchmark, briefly (in cache, one core, float lanes): ns per evaluation
// of every built-in lobe through the scalar lobe and the SIMD tiers.
#include <cmath>
#include <cstdio>

#include <specula/cost/lobe_cost.h>

int main() {
  specula::cost::Settings settings = specula::cost::Settings::quick();
  settings.streaming = false;
  settings.threaded = false;
  settings.doubles = false;
  settings.trials = 1;
  settings.trial_seconds = 0.001;
  settings.accuracy_points = 1 << 8;
  const specula::cost::Result result = specula::cost::run(settings);
  bool measured = !result.rows.empty();
  for (const specula::cost::Measurement& m : result.rows) measured = measured && std::isfinite(m.cache_ns);
  std::printf("cost: %zu lobes, %zu measurements on %s, every one timed: %s\n", result.lobes.size(),
              result.rows.size(), result.machine.target.c_str(), measured ? "yes" : "no");
  return measured ? 0 : 1;
}
