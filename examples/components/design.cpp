// specula::design: the lobe designer finds a cheap lobe closer to cⁿ over n ∈ [1, 50] than the
// paper's F_log (no image, font, OBJ, GL or HTTP library linked).
#include <algorithm>
#include <cstdio>

#include <specula/design/design.h>

int main() {
  specula::design::Settings s;
  s.target = "phong";
  s.lo = 1;
  s.hi = 50;
  s.operations = specula::design::parse_operations("fma,mul,max");
  s.max_cost = 3;
  s.threads = 1;
  s.measure_cost = false;
  const specula::design::Result r = specula::design::design(s);
  double log_error = 0, best = 1;
  for (const auto& l : r.references)
    if (l.id == "log") log_error = l.max_abs;
  for (const auto& l : r.front) best = std::min(best, l.max_abs);
  std::printf("design: best max |F - c^n| %.3f, F_log's %.3f\n", best, log_error);
  return best < log_error ? 0 : 1;
}
