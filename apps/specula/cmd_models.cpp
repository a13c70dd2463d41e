// specula models: the catalogue, as a table for people or JSON for programs.
#include <fmt/format.h>

#include "cli.h"
#include "specula/catalogue/catalogue.h"

namespace specula::cli {
namespace {

std::string params_text(const ModelInfo& m) {
  std::string text;
  for (const auto& p : m.params)
    text += fmt::format("{}{}={:g} {}", text.empty() ? "" : "  ", p.name, p.default_value, p.range_text());
  return text;
}

std::string models_table() {
  std::size_t id_width = 2, params_width = 6;
  for (const auto& m : models()) {
    id_width = std::max(id_width, m.id.size());
    params_width = std::max(params_width, params_text(m).size());
  }
  auto line = [&](auto id, auto kind, auto form, auto norm, auto params, auto summary) {
    return fmt::format("{:<{}}  {:<4}  {:<4}  {:<10}  {:<{}}  {}\n", id, id_width, kind, form, norm,
                       params, params_width, summary);
  };
  std::string out = line("id", "kind", "form", "norm", "params", "summary");
  for (const auto& m : models())
    out += line(m.id, to_string(m.kind), m.kind == ModelKind::lobe ? to_string(m.form) : "-",
                m.kind == ModelKind::lobe ? to_string(m.normalization) : "-", params_text(m), m.summary);
  return out;
}

}  // namespace

void add_models_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("models", "List every model: id, kind, form, normalization, parameters");
  cmd->footer(
      "Lobe models are F(c) with a form (rv: c = R·V, nh: c = N·H) and a coefficient k;\n"
      "full BRDFs take directions. Any id M with +ms appended (ggx+ms, log-normalized+ms, a model of\n"
      "yours + ms) is M with energy compensation, a full BRDF whose albedo is 1 where F = 1; with\n"
      "f0 < 1 GGX gives back the random walk's multiple scattering, the others Kulla-Conty's.\n"
      "Each published compensation is a suffix too: M+kulla-conty (the added lobe times F_ms),\n"
      "M+turquin-f0, M+turquin-f, M+turquin-favg (f_M times 1 + F (1 - E)/E at N.V, F = F0, F(N.V)\n"
      "or F_avg) and M+cycles (F = Cycles' F_ms); the scaled ones are not reciprocal and their\n"
      "albedo is the viewer's (docs/energy-compensation.md).\n"
      "Example:\n  specula models\n  specula models --json | jq '.[].id'\n"
      "  specula albedo --model ggx+turquin-f0 -p alpha=1 -p f0=0.04 --theta 0,60");
  auto json = std::make_shared<bool>(false);
  auto out = std::make_shared<std::string>();
  cmd->add_flag("--json", *json, "Print JSON instead of a table");
  cmd->add_option("--out,-o", *out, "Write to FILE (atomically) instead of stdout");
  cmd->callback([json, out] { write_output(*out, *json ? queries::models_json() : models_table()); });
}

}  // namespace specula::cli
