// The paper's Figs. 10-11: its model as GLSL, and spheres shaded with the normalized log lobe,
// the original log lobe and Schlick's.
#include <fmt/format.h>

#include "sections.h"
#include "specula/catalogue/catalogue.h"
#include "specula/glsl/glsl.h"
#include "specula/io/files.h"
#include "specula/lobes/closed_form.h"
#include "specula/normalize/log_coef_float.h"
#include "specula/render/image_io.h"
#include "specula/render/panel.h"
#include "specula/render/render.h"

namespace specula::report {
namespace {

/// The worst relative error of the float coefficient the shader computes, over n ∈ [1e-3, 1e6].
double shader_coef_error() {
  double worst = 0;
  for (const double n : log_spaced(1e-3, 1e6, 4001)) {
    const auto nf = static_cast<float>(n);
    worst = std::max(worst, std::abs(normalize::log_rv_approx<float>(nf) / lobes::log_rv(nf) - 1));
  }
  return worst;
}

std::string fig10(Context& context) {
  const Model model = make_model("log-normalized");
  const std::string source = glsl::model_glsl(model);
  context.write("fig10-log-normalized.glsl", source);
  const double error = shader_coef_error();
  context.findings["shader_coef_error"] = {error, show(error, 2)};
  return "<h3 id=\"fig10\">Fig. 10: the model in GLSL</h3>\n" +
         fmt::format(
             "<p>What <code>specula glsl --model log-normalized</code> emits (GLSL 3.30, GLSL ES 3.00 and WebGL 2 "
             "alike; every emitted shader passes glslangValidator in specula's tests). Unlike the paper's shader, "
             "the coefficient is exact: coef(n) is computed in the shader from two Chebyshev series fitted to the "
             "closed form (docs/math.md §4), within {} relative in float for n ∈ [10<sup>−3</sup>, 10<sup>6</sup>] "
             "(measured now, in float arithmetic identical to the shader's). Each function cites its source on its "
             "first line. File: <a href=\"fig10-log-normalized.glsl\">fig10-log-normalized.glsl</a>.</p>\n",
             show(error, 2)) +
         "<details><summary>The GLSL</summary><pre><code>" + xml_escape(source) + "</code></pre></details>\n";
}

}  // namespace

render::Image sphere(const Model& model, int size) {
  return render::render_cpu(render::default_scene(model), {size, size});
}

std::string panel_figure(Context& context, const std::string& name, const std::vector<render::LabelledImage>& panels,
                         const std::optional<render::HeatMaps>& heat_maps, const std::string& caption,
                         const std::string& command) {
  const render::ComparisonPanel panel = render::compose_comparison(panels, {}, {}, heat_maps);
  const auto path = context.dir() / (name + ".png");
  render::write_png(path, panel.image, {{"Software", "specula report"}, {"figure", name}});
  return context.png_figure(name, io::read_file(path), caption, command);
}

namespace {

std::string fig11(Context& context) {
  const int size = context.quick() ? 160 : 384;
  constexpr double n = 50;
  std::vector<render::LabelledImage> panels;
  for (const char* id : {"log-normalized", "log", "schlick"})
    panels.push_back({sphere(make_model(id, {{"n", n}}), size), fmt::format("{}  n = {:g}", id, n)});
  return "<h3 id=\"fig11\">Fig. 11: the spheres</h3>\n" +
         panel_figure(context, "fig11-spheres", panels, std::nullopt,
                      fmt::format("Local illumination as in the paper — ambient + Lambert diffuse + the specular lobe "
                                  "in rv form, one directional light — rendered by specula's CPU renderer ({0}×{0} per "
                                  "sphere, linear radiance, sRGB). The normalized lobe (left) reflects coef({1:g}) = "
                                  "{2:.4g} times more energy in its highlight than the bare F<sub>log</sub> (middle); "
                                  "Schlick's lobe (right) spreads it in a long tail.",
                                  size, n, lobes::log_rv(n)),
                      "specula compare --models log-normalized,log,schlick -p n=50 --out fig11.png");
}

}  // namespace

Section shader_section(Context& context) {
  context.progress("Figs. 10-11: the shader and the spheres");
  return {"shader", "Figs. 10–11: the shader and the spheres", fig10(context) + fig11(context)};
}

}  // namespace specula::report
