#pragma once
// What the commands share: model and parameter options, output options, and one function
// that registers each command. Every command is thin: parse, call the library, print.
#include <CLI/CLI.hpp>
#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>
#include <type_traits>
#include <string>
#include <vector>

#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/io/table.h"
#include "specula/io/values.h"
#include "specula/queries/queries.h"

namespace specula::cli {

/// An option's check that its value is one of E's names (its to_string): the one list that the
/// library parses the value from (choice_named), and the server reads too.
template <class E, std::size_t count>
CLI::IsMember one_of() {
  return CLI::IsMember(names_of<E, count>());
}

/// --model ID, --param NAME=VALUE (repeatable) and --form rv|nh.
struct ModelOptions {
  std::string id;
  std::vector<std::string> params;
  std::string form;
  std::optional<double> coef;

  void add_to(CLI::App& command, bool with_form = true);
  /// The same options, --model optional (a command that can do without a model).
  void add_optional_to(CLI::App& command, bool with_form = true);
  /// Adds --coef K: override a lobe model's k (e.g. with a coefficient from `normalize`).
  void add_coef_to(CLI::App& command);
  ParamValues param_values() const;
  /// True when a parameter has three values, R,G,B (-p eta=0.14,0.37,1.44): a coloured material,
  /// one model per channel (render).
  bool per_channel() const;
  /// The options of channel 0, 1 or 2: each three-valued parameter at that channel's value, the
  /// others as given. Throws InvalidArgument for a list that is not of three values.
  ModelOptions channel(int c) const;
  std::optional<Form> form_override() const;
  /// The model as queries name it; make() builds it (errors spell the options).
  queries::ModelSpec spec() const;
  Model make() const;
};

/// --format csv|json, --round DIGITS, --out FILE.
struct OutputOptions {
  std::string format = "csv";
  std::optional<int> round;
  std::string out;

  void add_to(CLI::App& command);
  /// Prints the table to stdout, or writes it atomically to --out.
  void emit(const io::Table& table) const;
};

/// Thrown after a check's report is printed when a property fails: exit code 1.
struct CheckFailed {};

/// io::parse_values, with the option's name in the error message; at most `max_values` values
/// (each command documents its cap, which keeps its worst case bounded in time and memory).
std::vector<double> option_values(std::string_view option, std::string_view spec,
                                  std::size_t max_values = io::kMaxValues);

/// A whole number as every integer option reads it: decimal digits only, a '-' before them for a
/// signed type (no '+', no spaces, no 0x, no exponent), within T's range; nullopt otherwise.
template <class T>
std::optional<T> strict_integer(std::string_view text) {
  const std::string_view digits = std::is_signed_v<T> && text.starts_with('-') ? text.substr(1) : text;
  if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos) return std::nullopt;
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

/// Gives every integer option of `app` and its commands (CLI11's INT and UINT types) the check
/// strict_integer makes, in addition to its own: "--seed -1", "--max-cost 0x2", "--seed ''" and
/// "--seed 18446744073709551616" are errors (exit 2), not a wrapped or default value.
void make_integer_options_strict(CLI::App& app);

/// Text to stdout, or atomically to `out` if non-empty.
void write_output(const std::string& out, const std::string& text);

void add_models_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_normalize_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_albedo_command(CLI::App& app);
void add_check_command(CLI::App& app);
void add_error_command(CLI::App& app);
void add_fit_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_glsl_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_lut_command(CLI::App& app);
void add_sample_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_serve_command(CLI::App& app);
void add_design_command(CLI::App& app);
void add_walk_command(CLI::App& app);
void add_verdict_command(CLI::App& app);

}  // namespace specula::cli
