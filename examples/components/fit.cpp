// specula::fit: the search for a formula recovers phong-normalized's k(n) = (n + 2)/(2π) from its
// values, with constants fitted (no image, font, OBJ, GL or HTTP library linked).
#include <cstdio>
#include <string>
#include <vector>

#include <specula/catalogue/catalogue.h>
#include <specula/fit/fit.h>

int main() {
  specula::fit::Data data{{"n"}, {{}}, {}};
  for (double n = 1; n <= 40; n += 3) {
    data.columns[0].push_back(n);
    data.target.push_back(specula::make_model("phong-normalized", {{"n", n}}).coef());
  }
  specula::fit::Options options;
  options.max_size = 7;
  options.enumerate_max_size = 7;
  options.target_error = 1e-9;
  options.time_limit_s = 30;
  options.threads = 1;
  const specula::fit::Result result = specula::fit::search(data, options);
  const specula::fit::Candidate& chosen = result.front[result.chosen];
  std::printf("fit: k(n) = %s, size %d, rms error %.1e (stopped by %s)\n",
              specula::expr::to_infix(specula::fit::rounded(chosen.formula, 6)).c_str(), chosen.size,
              chosen.train_error, std::string(specula::fit::to_string(result.stopped_by)).c_str());
  return chosen.train_error <= 1e-9 ? 0 : 1;
}
