#pragma once
// What the commands share: model and parameter options, output options, and one function
// that registers each command. Every command is thin: parse, call the library, print.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "specula/io/table.h"
#include "specula/models/model.h"

namespace specula::cli {

/// --model ID, --param NAME=VALUE (repeatable) and --form rv|nh.
struct ModelOptions {
  std::string id;
  std::vector<std::string> params;
  std::string form;

  void add_to(CLI::App& command, bool with_form = true);
  ParamValues param_values() const;
  std::optional<Form> form_override() const;
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

/// Text to stdout, or atomically to `out` if non-empty.
void write_output(const std::string& out, const std::string& text);

void add_models_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_normalize_command(CLI::App& app);
void add_report_command(CLI::App& app);

}  // namespace specula::cli
