// specula normalize: the coefficient k of a lobe in a form, exact and/or by quadrature.
#include "cli.h"

namespace specula::cli {
namespace {

// The documented cap: each n is a closed form or one quadrature (milliseconds; the strict
// condition: a search over θ_i); Ctrl-C stops them.
constexpr std::size_t kMaxN = 10'000;

struct NormalizeOptions {
  ModelOptions model;
  OutputOptions output;
  std::string n;
  std::string method = "auto";
  std::string compare;
  std::string condition = "normal";
  double step = 1;
};

io::Table normalize_table(const NormalizeOptions& o) {
  constexpr auto kOption = queries::Spelling::option;
  queries::NormalizeQuery q{o.model.id, o.model.param_values(), o.model.form_override(), {},
                            queries::normalize_method_named(o.method, kOption), o.compare,
                            queries::condition_named(o.condition, kOption), o.step};
  if (!o.n.empty()) q.n = option_values("--n", o.n, kMaxN);
  return queries::normalize_table(q, kOption);
}

}  // namespace

void add_normalize_command(CLI::App& app) {
  auto o = std::make_shared<NormalizeOptions>();
  auto* cmd = app.add_subcommand("normalize",
                                 "Normalizing coefficient k(n) of a lobe: albedo 1 at normal incidence");
  o->model.add_to(*cmd);
  cmd->add_option("--n", o->n, "Exponents: list or range (1:7  1:1000@50:log  paper50), at most 10000 values");
  cmd->add_option("--method", o->method,
                  "auto (closed form where known, else quadrature), exact, quadrature, or both "
                  "(adds coef_quadrature and rel_diff)")
      ->check(one_of<queries::NormalizeMethod, queries::kNormalizeMethodCount>());
  cmd->add_option("--compare", o->compare,
                  "Another lobe model: adds its k as coef_compare and delta = k_other·2π·Int − 1 "
                  "(the paper's Fig. 9 with log-paper)");
  cmd->add_option("--condition", o->condition,
                  "normal: albedo 1 at normal incidence (the paper's); strict: max over θ_i of the albedo = 1")
      ->capture_default_str()
      ->check(one_of<queries::Condition, queries::kConditionCount>());
  cmd->add_option("--step", o->step, "With --condition strict: θ_i grid step (degrees) before refinement")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 45.0));
  o->output.add_to(*cmd);
  cmd->footer(
      "k solves k · 2π ∫ F(c) cos θ sin θ dθ = 1 with the lobe centred on the normal (docs/math.md §1);\n"
      "the lobe's only parameter swept is n, others come from --param. Examples:\n"
      "  specula normalize --model log --n 1:7 --round 3        # the paper's Fig. 5 table\n"
      "  specula normalize --model log --n 1:1000@50:log --method both\n"
      "  specula normalize --model log --n paper50 --compare log-paper   # the paper's Fig. 9\n"
      "  specula normalize --model gauss --form nh --n 1,10,100\n"
      "  specula normalize --model log --form nh --n 20 --condition strict");
  cmd->callback([o] { o->output.emit(normalize_table(*o)); });
}

}  // namespace specula::cli
