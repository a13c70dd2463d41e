// The paper's Figs. 10-11: its model as GLSL, and spheres shaded with the normalized log lobe,
// the original log lobe and Schlick's.
#include <fmt/format.h>

#include "sections.h"
#include "specula/gl/glsl.h"
#include "specula/normalize/closed_form.h"
#include "specula/normalize/log_coef_float.h"

namespace specula::report {
namespace {

/// The worst relative error of the float coefficient the shader computes, over n ∈ [1e-3, 1e6].
double shader_coef_error() {
  double worst = 0;
  for (const double n : log_spaced(1e-3, 1e6, 4001)) {
    const auto nf = static_cast<float>(n);
    worst = std::max(worst, std::abs(normalize::log_rv_approx<float>(nf) / normalize::log_rv(nf) - 1));
  }
  return worst;
}

std::string fig10(Context& context) {
  const Model model = make_model("log-normalized");
  const std::string glsl = gl::model_glsl(model);
  context.write("fig10-log-normalized.glsl", glsl);
  const double error = shader_coef_error();
  context.findings["shader_coef_error"] = {error, show(error, 2)};
  return "<h3 id=\"fig10\">Fig. 10: the model in GLSL</h3>\n" +
         fmt::format(
             "<p>What <code>specula glsl --model log-normalized</code> emits (GLSL 3.30, GLSL ES 3.00 and WebGL 2 "
             "alike; every emitted shader passes glslangValidator in specula's tests). Unlike the paper's shader, "
             "the coefficient is exact: coef(n) is computed in the shader from two Chebyshev series fitted to the "
             "closed form (MATH.md §4), within {} relative in float for n ∈ [10<sup>−3</sup>, 10<sup>6</sup>] "
             "(measured now, in float arithmetic identical to the shader's). Each function cites its source on its "
             "first line. File: <a href=\"fig10-log-normalized.glsl\">fig10-log-normalized.glsl</a>.</p>\n",
             show(error, 2)) +
         "<details><summary>The GLSL</summary><pre><code>" + html_escape(glsl) + "</code></pre></details>\n";
}

}  // namespace

Section shader_section(Context& context) {
  context.progress("Figs. 10-11: the shader and the spheres");
  return {"shader", "Figs. 10–11: the shader and the spheres", fig10(context)};
}

}  // namespace specula::report
