// Beyond the paper: the log lobes against the lobe they approximate, cosⁿθ (the paper's
// "Blinn-Phong" F_B, docs/math.md §2 `phong`), as difference images at several n.
#include <fmt/format.h>

#include "sections.h"
#include "specula/catalogue/catalogue.h"

namespace specula::report {
namespace {

std::string difference_figure(Context& context, double n, int size) {
  const Model reference = make_model("phong-normalized", {{"n", n}});
  std::vector<render::LabelledImage> panels;
  panels.push_back({sphere(reference, size), fmt::format("phong-normalized  n = {:g}", n)});
  for (const char* id : {"log-normalized", "log"})
    panels.push_back({sphere(make_model(id, {{"n", n}}), size), fmt::format("{}  n = {:g}", id, n)});
  render::HeatMaps heat_maps{panels.front().image, std::nullopt, "|ΔL| vs phong-normalized, linear"};
  return panel_figure(context, fmt::format("differences-n{:g}", n), panels, heat_maps,
                      fmt::format("n = {:g}. Top: the exactly normalized cosⁿθ lobe, the normalized and the bare "
                                  "F<sub>log</sub>. Bottom: |ΔL| of linear luminance against the first, on one scale.",
                                  n),
                      fmt::format("specula compare --models phong-normalized,log-normalized,log -p n={:g} "
                                  "--diff phong-normalized --out differences.png",
                                  n));
}

}  // namespace

Section differences_section(Context& context) {
  context.progress("Difference images against cosⁿθ");
  const std::vector<double> ns = context.quick() ? std::vector<double>{5, 100} : std::vector<double>{5, 20, 100, 500};
  std::string html =
      "<p>Where does the cheap lobe differ on screen? Spheres shaded as in Fig. 11 with the exactly normalized "
      "cosⁿθ lobe and with F<sub>log</sub>, normalized and not. Normalized, F<sub>log</sub> differs from cosⁿθ "
      "only in the shape of the highlight (it is cut off at cosⁿθ = 1/8 and slightly fuller inside); the bare "
      "lobe loses the highlight's energy, more as n grows.</p>\n<div class=\"grid\">\n";
  for (const double n : ns) html += difference_figure(context, n, context.quick() ? 96 : 256);
  return {"differences", "Beyond the paper: difference images against cosⁿθ", html + "</div>\n"};
}

}  // namespace specula::report
