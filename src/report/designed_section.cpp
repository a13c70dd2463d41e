// Beyond the paper: the lobe designer (docs/designer.md) run on the paper's own problem — lobes
// against cⁿ over n ∈ [1, 1000] — with F_log and Schlick's lobe measured beside them, and which
// designed lobes beat F_log on both error and measured cost.
#include <cmath>
#include <fmt/format.h>
#include <tuple>

#include "sections.h"
#include "specula/design/design.h"
#include "specula/design/output.h"
#include "specula/report/design_page.h"
#include "specula/report/plot.h"

namespace specula::report {
namespace {

const design::Lobe* reference(const design::Result& r, std::string_view id) {
  for (const auto& l : r.references)
    if (l.id == id) return &l;
  return nullptr;
}

std::string designed_table(const design::Result& r, std::string_view target = "cⁿ") {
  std::vector<std::vector<std::string>> rows;
  const auto row = [&](const design::Lobe& l) {
    rows.push_back({xml_escape(l.id), show(l.max_abs), show(l.ns_per_eval, 3), l.ops > 0 ? std::to_string(l.ops) : "–",
                    l.reference ? "–" : xml_escape(l.check), "<code>" + xml_escape(l.formula) + "</code>"});
  };
  for (const auto& l : r.front) row(l);
  for (const auto& l : r.references) row(l);
  return html_table({"lobe", fmt::format("max |F − {}|", target), "ns per value", "ops", "check", "F"}, rows, "models");
}

// Whether l costs less than ref: measured faster, or within the timing's noise (10 %) and fewer
// operations (timings this close swap from run to run on a shared machine; operations do not).
bool cheaper(const design::Lobe& l, const design::Lobe& ref) {
  if (l.ns_per_eval < ref.ns_per_eval) return true;
  return l.ns_per_eval <= 1.1 * ref.ns_per_eval && l.ops > 0 && ref.ops > 0 && l.ops < ref.ops;
}

// The members that beat `ref` on both axes, as prose.
std::string dominating(const design::Result& r, const design::Lobe* ref) {
  if (!ref || !std::isfinite(ref->ns_per_eval)) return "";
  std::vector<std::string> ids;
  for (const auto& l : r.front)
    if (l.max_abs < ref->max_abs && cheaper(l, *ref))
      ids.push_back(fmt::format("{} ({} at {:.2f}× the cost, {} operations against {})", l.id, show(l.max_abs, 3),
                                l.ns_per_eval / ref->ns_per_eval, l.ops, ref->ops));
  return ids.empty() ? fmt::format("No designed lobe beats {} on both error and cost.", ref->id)
                     : fmt::format("Beating {} ({}, {} ns) on both: {}.", ref->id, show(ref->max_abs, 3),
                                   show(ref->ns_per_eval, 3), fmt::join(ids, ", "));
}

// The paper's premise, that F_log is cheaper than pow, as this run measured it on the CPU and (where
// timed) on the GPU: findings for the claims table.
void premise_findings(Context& context, const design::Result& r) {
  const design::Lobe *log = reference(r, "log"), *pow = reference(r, "phong");
  if (!log || !pow || !std::isfinite(log->ns_per_eval) || !std::isfinite(pow->ns_per_eval)) return;
  context.findings["premise_cpu_ratio"] = {log->ns_per_eval / pow->ns_per_eval,
                                           fmt::format("F<sub>log</sub> {} ns, pow {} ns", show(log->ns_per_eval, 3),
                                                       show(pow->ns_per_eval, 3))};
  if (!std::isfinite(log->gpu_ps_per_eval) || !std::isfinite(pow->gpu_ps_per_eval)) {
    context.findings["premise_gpu_note"] = {NAN, xml_escape(r.gpu_note.empty() ? "not timed on a GPU" : r.gpu_note)};
    return;
  }
  context.findings["premise_gpu_ratio"] = {log->gpu_ps_per_eval / pow->gpu_ps_per_eval,
                                           fmt::format("F<sub>log</sub> {} ps, pow {} ps", show(log->gpu_ps_per_eval, 3),
                                                       show(pow->gpu_ps_per_eval, 3))};
  context.findings["premise_gpu_note"] = {NAN, xml_escape(r.gpu_note)};
}

}  // namespace

Section designed_section(Context& context) {
  context.progress("designed lobes");
  design::Settings s;
  s.target = "phong";
  s.lo = 1;
  s.hi = 1000;
  s.max_cost = context.quick() ? 3 : 5;
  if (context.quick()) s.operations = design::parse_operations("fma,mul,max");  // the lobes that win, in seconds
  if (!context.quick()) s.gpu_timer = context.gpu_timer();
  const design::Result r = design::design(s);
  premise_findings(context, r);
  context.write("designed-models.toml", design::models_toml(r));
  context.write("designed-front.csv", design::front_csv(r));
  const std::string command = fmt::format("specula design --target phong --range n=1:1000 --max-cost {} --out D", s.max_cost);
  const std::string html =
      fmt::format("<p>The paper picks F_log by hand. <code>specula design</code> (docs/designer.md) searches instead: "
                  "every lobe shape up to cost {} in {} ({} shapes, {:.0f} s), each shape's constants fitted per n for the largest error and given laws "
                  "in n, each finished lobe's error measured exactly over every c and every n ∈ [1, 1000], each timed "
                  "as compiled native code beside the references in one run. {} {}</p>\n",
                  s.max_cost,
                  context.quick() ? "fused multiply-adds, max and squares"
                                  : "fused multiply-adds, max, squares, divisions, square roots, exp and log₂",
                  r.forms_total, r.seconds, dominating(r, reference(r, "log")),
                  dominating(r, reference(r, "schlick"))) +
      context.svg_figure("designed-front", to_svg(design_front_chart(r)),
                         "The designed front (the staircase: each step a lobe no cheaper lobe matches) and the "
                         "reference lobes on the same axes, measured in the same run on the machine that wrote this "
                         "report. " + r.cost_note + ".",
                         command, "<a href=\"designed-front.csv\">designed-front.csv</a>, "
                                  "<a href=\"designed-models.toml\">designed-models.toml</a>") +
      designed_table(r);
  return {"designed", "Beyond the paper: designed lobes", html};
}

Section engine_terms_section(Context& context) {
  struct Term {
    std::string_view target, what;
    int cost, quick_cost;
    std::string_view ops;
  };
  // Costs that finish in seconds each (release, two cores); the quick report's in one or two.
  constexpr Term kTerms[] = {{"fresnel-dielectric", "the exact dielectric Fresnel over η ∈ [1.2, 2.5]", 4, 1, "fma,mul,max"},
                             {"smith-g2-ggx", "the height-correlated Smith G₂ of GGX over α ∈ [0.05, 1]", 3, 1, "fma,mul,max"},
                             {"env-brdf-b-ggx", "the split-sum bias B(NoV, r) of GGX", 4, 1, "fma,mul,add,max"}};
  std::string html =
      "<p>Engines approximate the other terms of a microfacet BRDF by hand: Schlick's Fresnel, the fast Smith "
      "form, Karis's <code>EnvBRDFApprox</code>. The designer searches against each exact term, the engines' forms "
      "measured and timed beside its members in the same run (docs/designer.md, \"Targets beyond lobes\"; larger "
      "searches there find more).</p>\n";
  for (const Term& t : kTerms) {
    context.progress(fmt::format("designed terms: {}", t.target));
    design::Settings s;
    s.target = std::string(t.target);
    s.variables = design::default_variables(s.target);
    const design::DefaultRange range = design::default_range(s.target, s.variables);
    std::tie(s.param, s.lo, s.hi) = std::tie(range.param, range.lo, range.hi);
    s.max_cost = context.quick() ? t.quick_cost : t.cost;
    s.operations = design::parse_operations(t.ops);
    s.measure_cost = !context.quick();  // the quick report's tests read the errors; compiling three times costs 10 s there
    s.certify = !context.quick();       // … nor bounding them (30 s under the sanitizers) or
    s.refit_references = !context.quick();  // refitting the engines' forms (40 s)
    const design::Result r = design::design(s);
    std::string beaten;
    for (const auto& ref : r.references)
      if (ref.max_abs > 0) beaten.append(" ").append(dominating(r, &ref));
    const std::string command =
        fmt::format("specula design --target {} --ops {} --max-cost {} --out D", t.target, t.ops, s.max_cost);
    html += fmt::format("<h3>{}</h3>\n<p>Against {}: {} shapes up to cost {} in {:.0f} s.{}</p>\n", t.target, t.what,
                        r.forms_total, s.max_cost, r.seconds, beaten) +
            context.svg_figure(fmt::format("designed-{}", t.target), to_svg(design_front_chart(r)),
                               fmt::format("The designed front against {} and the engines' approximations, measured "
                                           "in the same run. {}.", t.target, r.cost_note),
                               command, "") +
            designed_table(r, t.target);
  }
  return {"terms", "Beyond the paper: the engines' terms designed", html};
}

}  // namespace specula::report
