// specula normalize: the coefficient k of a lobe in a form, exact and/or by quadrature.
#include <fmt/format.h>

#include "cli.h"
#include "specula/analysis/check.h"
#include "specula/error.h"
#include "specula/io/values.h"
#include "specula/normalize/normalize.h"

namespace specula::cli {
namespace {

struct NormalizeOptions {
  ModelOptions model;
  OutputOptions output;
  std::string n;
  std::string method = "auto";
  std::string compare;
  std::string condition = "normal";
  double step = 1;
};

normalize::Method parse_method(const std::string& method) {
  if (method == "exact" || method == "both") return normalize::Method::exact;
  if (method == "quadrature") return normalize::Method::quadrature;
  return normalize::Method::automatic;
}

io::Table normalize_table(const NormalizeOptions& o) {
  ParamValues params = o.model.param_values();
  if (params.contains("n")) throw InvalidArgument("give n with --n, not --param");
  const auto form = o.model.form_override();
  const bool both = o.method == "both";
  const bool strict = o.condition == "strict";
  if (strict && (o.method == "exact" || both))
    throw InvalidArgument("the strict condition has no closed form: drop --method or use quadrature");
  const normalize::Method method = parse_method(o.method);

  io::Table table{{"n", "coef"}, {}, {{"model", o.model.id}, {"method", o.method}, {"condition", o.condition}}};
  if (both) table.columns.insert(table.columns.end(), {"coef_quadrature", "rel_diff"});
  if (!o.compare.empty()) table.columns.insert(table.columns.end(), {"coef_compare", "delta"});

  const auto ns = o.n.empty() ? std::vector<double>{make_model(o.model.id).param("n")}
                              : option_values("--n", o.n);
  for (const double n : ns) {
    const Model m = lobe_model_at("normalize", o.model.id, params, n, form);
    if (table.meta.size() == 3) table.meta.emplace_back("form", to_string(m.form()));
    const double coef = strict ? analysis::strict_coefficient(m, o.step)
                               : normalize::coefficient(m.lobe(), m.form(), method);
    std::vector<double> row{n, coef};
    if (both) {
      const double q = normalize::quadrature(m.lobe(), m.form());
      row.insert(row.end(), {q, (q - coef) / coef});
    }
    if (!o.compare.empty()) {
      const double other = lobe_model_at("--compare", o.compare, {}, n).coef();
      row.insert(row.end(), {other, (other - coef) / coef});  // k_other·2π·Int − 1
    }
    table.rows.push_back(std::move(row));
  }
  if (!o.compare.empty()) table.meta.emplace_back("compare", o.compare);
  return table;
}

}  // namespace

void add_normalize_command(CLI::App& app) {
  auto o = std::make_shared<NormalizeOptions>();
  auto* cmd = app.add_subcommand("normalize",
                                 "Normalizing coefficient k(n) of a lobe: albedo 1 at normal incidence");
  o->model.add_to(*cmd);
  cmd->add_option("--n", o->n, "Exponents: list or range (1:7  1:1000@50:log  paper50)");
  cmd->add_option("--method", o->method,
                  "auto (closed form where known, else quadrature), exact, quadrature, or both "
                  "(adds coef_quadrature and rel_diff)")
      ->check(CLI::IsMember({"auto", "exact", "quadrature", "both"}));
  cmd->add_option("--compare", o->compare,
                  "Another lobe model: adds its k as coef_compare and delta = k_other·2π·Int − 1 "
                  "(the paper's Fig. 9 with log-paper)");
  cmd->add_option("--condition", o->condition,
                  "normal: albedo 1 at normal incidence (the paper's); strict: max over θ_i of the albedo = 1")
      ->capture_default_str()
      ->check(CLI::IsMember({"normal", "strict"}));
  cmd->add_option("--step", o->step, "With --condition strict: θ_i grid step (degrees) before refinement")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 45.0));
  o->output.add_to(*cmd);
  cmd->footer(
      "k solves k · 2π ∫ F(c) cos θ sin θ dθ = 1 with the lobe centred on the normal (MATH.md §1);\n"
      "the lobe's only parameter swept is n, others come from --param. Examples:\n"
      "  specula normalize --model log --n 1:7 --round 3        # the paper's Fig. 5 table\n"
      "  specula normalize --model log --n 1:1000@50:log --method both\n"
      "  specula normalize --model log --n paper50 --compare log-paper   # the paper's Fig. 9\n"
      "  specula normalize --model gauss --form nh --n 1,10,100\n"
      "  specula normalize --model log --form nh --n 20 --condition strict");
  cmd->callback([o] { o->output.emit(normalize_table(*o)); });
}

}  // namespace specula::cli
