// specula::queries: what the CLI's analysis commands and the server compute, called directly —
// `specula normalize` as a table, `specula glsl`'s function, and a model's k(n) as data for fit.
#include <cstdio>
#include <string>
#include <vector>

#include <specula/io/table.h>
#include <specula/queries/queries.h>

int main() {
  using namespace specula::queries;
  NormalizeQuery query;
  query.model = ModelRef{"log-normalized"};
  query.n = {20};
  const specula::io::Table table = normalize_table(query, Spelling::option);

  ModelSpec ggx;
  ggx.model = ModelRef{"ggx"};
  ggx.params = {{"alpha", 0.3}};
  const std::string glsl = glsl_function(make(ggx, Spelling::option), specula::glsl::Dialect::webgl2);

  ModelSpec phong;
  phong.model = ModelRef{"phong-normalized"};
  const std::vector<double> n{1, 10, 100};
  const specula::fit::Data data = normalization_data(phong, n, std::nullopt, Spelling::option);

  std::printf("queries: normalize log-normalized at n = 20: k = %.5f; glsl ggx: %zu bytes; "
              "fit data: %zu rows\n", table.rows.at(0).at(1), glsl.size(), data.target.size());
  const bool ok = table.rows.size() == 1 && data.target.size() == 3 && glsl.find("specula_brdf") != std::string::npos;
  return ok ? 0 : 1;
}
