#pragma once
// Reading a request's JSON body field by field: each accessor checks the type, finiteness and
// count of one field and throws InvalidField naming it, so that every 400 says which field is bad.
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "specula/models/model.h"
#include "specula/queries/queries.h"

namespace specula::serve {

class Fields {
 public:
  /// Parses `body` as a JSON object; InvalidField "body" when it is malformed or not an object.
  /// `known` lists the keys the endpoint reads: any other key is an error (a misspelt field
  /// would otherwise be ignored silently).
  Fields(std::string_view body, std::set<std::string, std::less<>> known);

  bool has(std::string_view key) const;

  std::string text(std::string_view key) const;  ///< required string
  std::string text_or(std::string_view key, std::string fallback) const;
  double number(std::string_view key) const;  ///< required finite number
  double number_or(std::string_view key, double fallback) const;
  /// A whole number in [low, high].
  std::int64_t integer_or(std::string_view key, std::int64_t fallback, std::int64_t low, std::int64_t high) const;
  bool flag_or(std::string_view key, bool fallback) const;
  /// A list of names: an array of strings, or one comma-separated string.
  std::vector<std::string> names(std::string_view key) const;

  /// An array of finite numbers or a range string as the CLI takes it ("1:1000@50:log"),
  /// non-empty, at most `max_count` values.
  std::vector<double> values(std::string_view key, std::size_t max_count) const;
  std::vector<double> values_or(std::string_view key, std::string_view fallback_spec, std::size_t max_count) const;

  /// {"name": number, …} as ParamValues ("params", optional).
  ParamValues params() const;
  /// The model `key` names: an id or inline definition (a string), or a definition object
  /// (serve/definition.h), whose errors name the key at fault ("model.lobe").
  queries::ModelRef model_ref(std::string_view key) const;
  /// model (model_ref), params, form, and coef when `with_coef`.
  queries::ModelSpec model(bool with_coef = true) const;

  /// The object under `key` (an object), as Fields with its own known keys.
  Fields object(std::string_view key, std::set<std::string, std::less<>> known) const;
  const nlohmann::json& raw(std::string_view key) const;

 private:
  Fields(nlohmann::json object, std::string prefix, std::set<std::string, std::less<>> known);
  void reject_unknown() const;
  std::string name(std::string_view key) const;  ///< prefix + key: "data.columns"
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;

  nlohmann::json json_;
  std::string prefix_;
  std::set<std::string, std::less<>> known_;
};

/// A finite number from JSON (not a bool), or nullopt.
std::optional<double> finite_number(const nlohmann::json& value);

}  // namespace specula::serve
