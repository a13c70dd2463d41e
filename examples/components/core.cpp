// specula::core alone: a model, its exact normalization, its albedo by cubature and its GLSL,
// with no image, font, OBJ, GL or HTTP library linked.
#include <cstdio>

#include <specula/analysis/albedo.h>
#include <specula/glsl/glsl.h>
#include <specula/catalogue/catalogue.h>

int main() {
  const specula::Model model = specula::make_model("log-normalized", {{"n", 20}});
  const double albedo = specula::analysis::albedo(model, 0.0).value;
  const std::size_t glsl = specula::glsl::model_glsl(model).size();
  std::printf("core: k = %.6f, albedo at normal incidence = %.9f, GLSL %zu bytes\n", model.coef(), albedo, glsl);
  return albedo > 0.999 && albedo < 1.001 ? 0 : 1;
}
