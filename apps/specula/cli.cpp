#include "cli.h"

#include <algorithm>
#include <fmt/format.h>
#include <iostream>

#include "specula/exceptions.h"
#include "specula/io/files.h"
#include "specula/io/values.h"

namespace specula::cli {

void ModelOptions::add_to(CLI::App& command, bool with_form) {
  add_optional_to(command, with_form);
  command.get_option("--model")->required();
}

void ModelOptions::add_optional_to(CLI::App& command, bool with_form) {
  command.add_option("--model,-m", id,
                     "Model id (see `specula models`; your own with --models FILE), or inline: "
                     "'lobe: FORMULA' (in c) or 'brdf: FORMULA' (in nl, nv, nh, vh, lv); an inline "
                     "model's parameters take their values from -p (else 1)");
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

bool ModelOptions::per_channel() const {
  return std::any_of(params.begin(), params.end(), [](const std::string& p) { return p.find(',') != std::string::npos; });
}

ModelOptions ModelOptions::channel(int c) const {
  ModelOptions one = *this;
  for (std::string& p : one.params) {
    const auto eq = p.find('=');
    if (eq == std::string::npos || p.find(',') == std::string::npos) continue;
    std::vector<std::string> values;
    for (std::size_t at = eq + 1;;) {
      const auto comma = p.find(',', at);
      values.push_back(p.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    if (values.size() != 3)
      throw InvalidArgument(fmt::format("--param '{}': give one value, or three (R,G,B) for a coloured material", p));
    p = p.substr(0, eq + 1) + values[static_cast<std::size_t>(c)];
  }
  return one;
}

std::optional<Form> ModelOptions::form_override() const {
  if (form.empty()) return std::nullopt;
  return queries::form_named(form, queries::Spelling::option);
}

queries::ModelSpec ModelOptions::spec() const { return {id, param_values(), form_override(), coef}; }

Model ModelOptions::make() const { return queries::make(spec(), queries::Spelling::option); }

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

std::vector<double> option_values(std::string_view option, std::string_view spec, std::size_t max_values) {
  try {
    return io::parse_values(spec, max_values);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(fmt::format("{}: {}", option, e.what()));
  }
}

void write_output(const std::string& out, const std::string& text) {
  if (out.empty()) {
    std::cout << text << std::flush;
  } else {
    io::write_file_atomically(out, text);
  }
}

namespace {

CLI::Validator strict_integer_check(bool is_signed) {
  return CLI::Validator(
      [is_signed](std::string& text) -> std::string {
        const bool ok = is_signed ? strict_integer<std::int64_t>(text).has_value() : strict_integer<std::uint64_t>(text).has_value();
        if (ok) return {};
        return fmt::format("'{}' is not a whole number{} (decimal digits only{})", text,
                           is_signed ? "" : " ≥ 0", is_signed ? ", a '-' before them if negative" : "");
      },
      "");
}

}  // namespace

void make_integer_options_strict(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    const std::string_view base = std::string_view(type).substr(0, type.find(':'));
    if (base == "INT" || base == "UINT") option->check(strict_integer_check(base == "INT"));
  }
  for (CLI::App* command : app.get_subcommands({})) make_integer_options_strict(*command);
}

}  // namespace specula::cli
