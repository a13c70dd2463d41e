#include "cli.h"

#include <fmt/format.h>
#include <iostream>

#include "specula/error.h"
#include "specula/io/values.h"

namespace specula::cli {

void ModelOptions::add_to(CLI::App& command, bool with_form) {
  command.add_option("--model,-m", id, "Model id (see `specula models`)")->required();
  command.add_option("--param,-p", params, "Parameter as NAME=VALUE, repeatable (e.g. -p n=20)");
  if (with_form)
    command.add_option("--form", form, "rv (c = R·V) or nh (c = N·H); default: the model's own");
}

void ModelOptions::add_coef_to(CLI::App& command) {
  command.add_option("--coef", coef, "Use this coefficient k instead of the model's own (lobe models)");
}

ParamValues ModelOptions::param_values() const {
  ParamValues values;
  for (const auto& p : params) {
    const auto eq = p.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidArgument(fmt::format("malformed --param '{}': expected NAME=VALUE", p));
    const std::string name = p.substr(0, eq);
    if (values.contains(name)) throw InvalidArgument(fmt::format("--param {} is given twice", name));
    values[name] = io::parse_number(std::string_view(p).substr(eq + 1), "--param " + name);
  }
  return values;
}

std::optional<Form> ModelOptions::form_override() const {
  if (form.empty()) return std::nullopt;
  return parse_form(form);
}

Model ModelOptions::make() const {
  Model m = make_model(id, param_values(), form_override());
  return coef ? m.with_coef(*coef) : m;
}

std::vector<std::pair<std::string, std::string>> model_meta(const Model& m) {
  std::vector<std::pair<std::string, std::string>> meta{{"model", std::string(m.id())}};
  for (std::size_t i = 0; i < m.params().size(); ++i)
    meta.emplace_back(std::string(m.info().params[i].name), io::format_number(m.params()[i]));
  if (m.is_lobe()) {
    meta.emplace_back("form", to_string(m.form()));
    meta.emplace_back("coef", io::format_number(m.coef()));
  }
  return meta;
}

void OutputOptions::add_to(CLI::App& command) {
  command.add_option("--format", format, "csv (default) or json")
      ->check(CLI::IsMember({"csv", "json"}));
  command.add_option("--round", round, "Print numbers with this many decimals (default: full precision)")
      ->check(CLI::Range(0, 17));
  command.add_option("--out,-o", out, "Write to FILE (atomically) instead of stdout");
}

void OutputOptions::emit(const io::Table& table) const {
  write_output(out, format == "json" ? io::to_json(table, round) : io::to_csv(table, round));
}

std::vector<double> option_values(std::string_view option, std::string_view spec) {
  try {
    return io::parse_values(spec);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", option, e.what()));
  }
}

Model lobe_model_at(std::string_view command, std::string_view id, ParamValues params, double n,
                    std::optional<Form> form) {
  if (!make_model(id).is_lobe())
    throw InvalidArgument(fmt::format("{} works on lobe models; '{}' is a full BRDF", command, id));
  params["n"] = n;
  return make_model(id, params, form);
}

void write_output(const std::string& out, const std::string& text) {
  if (out.empty()) {
    std::cout << text << std::flush;
  } else {
    io::write_file_atomically(out, text);
  }
}

}  // namespace specula::cli
