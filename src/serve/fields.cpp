#include "fields.h"

#include <cmath>
#include <fmt/format.h>

#include "definition.h"
#include "specula/exceptions.h"
#include "specula/io/values.h"

namespace specula::serve {
namespace {

using Json = nlohmann::json;

const char* type_name(const Json& value) {
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_boolean()) return "a boolean";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "null";
}

Json parse_object(std::string_view body) {
  // nlohmann's parser ends its input at a NUL byte, which would accept `{…}` followed by anything.
  if (body.find('\0') != std::string_view::npos) throw InvalidField("body", "the body is not valid JSON (a NUL byte)");
  // nlohmann's parser skips a UTF-8 byte order mark, which JSON over the network may not carry
  // (RFC 8259 §8.1): refused, as any other byte before the value is.
  if (body.starts_with("\xEF\xBB\xBF")) throw InvalidField("body", "the body is not valid JSON (it starts with a byte order mark)");
  Json json = Json::parse(body, nullptr, false);
  if (json.is_discarded()) throw InvalidField("body", "the body is not valid JSON");
  if (!json.is_object())
    throw InvalidField("body", fmt::format("the body must be a JSON object, got {}", type_name(json)));
  return json;
}

}  // namespace

std::optional<double> finite_number(const Json& value) {
  if (!value.is_number()) return std::nullopt;
  const double x = value.get<double>();
  if (!std::isfinite(x)) return std::nullopt;
  return x;
}

Fields::Fields(std::string_view body, std::set<std::string, std::less<>> known)
    : Fields(parse_object(body), "", std::move(known)) {}

Fields::Fields(Json object, std::string prefix, std::set<std::string, std::less<>> known)
    : json_(std::move(object)), prefix_(std::move(prefix)), known_(std::move(known)) {
  reject_unknown();
}

void Fields::reject_unknown() const {
  for (const auto& [key, value] : json_.items())
    if (!known_.contains(key))
      fail(key, fmt::format("unknown field '{}' (known: {})", name(key), fmt::join(known_, ", ")));
}

std::string Fields::name(std::string_view key) const { return prefix_ + std::string(key); }

void Fields::fail(std::string_view key, const std::string& message) const {
  throw InvalidField(name(key), message);
}

bool Fields::has(std::string_view key) const {
  const auto it = json_.find(key);
  return it != json_.end() && !it->is_null();
}

const Json& Fields::raw(std::string_view key) const {
  if (!has(key)) fail(key, fmt::format("{} is required", name(key)));
  return json_.find(key).value();
}

std::string Fields::text(std::string_view key) const {
  const Json& value = raw(key);
  if (!value.is_string()) fail(key, fmt::format("{} must be a string, got {}", name(key), type_name(value)));
  return value.get<std::string>();
}

std::string Fields::text_or(std::string_view key, std::string fallback) const {
  return has(key) ? text(key) : std::move(fallback);
}

double Fields::number(std::string_view key) const {
  const Json& value = raw(key);
  const auto x = finite_number(value);
  if (!x) fail(key, fmt::format("{} must be a finite number, got {}", name(key), value.is_number() ? value.dump() : type_name(value)));
  return *x;
}

double Fields::number_or(std::string_view key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

std::int64_t Fields::integer_or(std::string_view key, std::int64_t fallback, std::int64_t low,
                                std::int64_t high) const {
  if (!has(key)) return fallback;
  const double x = number(key);
  if (x != std::floor(x) || x < static_cast<double>(low) || x > static_cast<double>(high))
    fail(key, fmt::format("{} must be a whole number in [{}, {}], got {}", name(key), low, high, x));
  return static_cast<std::int64_t>(x);
}

bool Fields::flag_or(std::string_view key, bool fallback) const {
  if (!has(key)) return fallback;
  const Json& value = raw(key);
  if (!value.is_boolean()) fail(key, fmt::format("{} must be true or false, got {}", name(key), type_name(value)));
  return value.get<bool>();
}

std::vector<std::string> Fields::names(std::string_view key) const {
  const Json& value = raw(key);
  std::vector<std::string> list;
  if (value.is_string()) {
    for (const auto name : io::split(value.get_ref<const std::string&>(), ',')) list.emplace_back(name);
    return list;
  }
  if (!value.is_array()) fail(key, fmt::format("{} must be an array of strings, got {}", name(key), type_name(value)));
  for (const auto& item : value) {
    if (!item.is_string()) fail(key, fmt::format("{} must hold strings only, got {}", name(key), type_name(item)));
    list.push_back(item.get<std::string>());
  }
  return list;
}

std::vector<double> Fields::values(std::string_view key, std::size_t max_count) const {
  const Json& value = raw(key);
  std::vector<double> list;
  if (value.is_string()) {
    try {
      list = io::parse_values(value.get<std::string>(), max_count);
    } catch (const InvalidArgument& e) {
      fail(key, fmt::format("{}: {}", name(key), e.what()));
    }
    return list;
  }
  if (!value.is_array())
    fail(key, fmt::format("{} must be an array of numbers or a range such as \"1:1000@50:log\", got {}",
                          name(key), type_name(value)));
  if (value.empty()) fail(key, fmt::format("{} is empty", name(key)));
  if (value.size() > max_count)
    fail(key, fmt::format("{} has {} values; at most {} per request", name(key), value.size(), max_count));
  for (std::size_t i = 0; i < value.size(); ++i) {
    const auto x = finite_number(value[i]);
    if (!x)
      fail(key, fmt::format("{}[{}] must be a finite number, got {}", name(key), i,
                            value[i].is_number() ? value[i].dump() : type_name(value[i])));
    list.push_back(*x);
  }
  return list;
}

std::vector<double> Fields::values_or(std::string_view key, std::string_view fallback_spec,
                                      std::size_t max_count) const {
  return has(key) ? values(key, max_count) : io::parse_values(fallback_spec, max_count);
}

ParamValues Fields::params() const {
  ParamValues params;
  if (!has("params")) return params;
  const Json& value = raw("params");
  if (!value.is_object())
    fail("params", fmt::format("{} must be an object such as {{\"n\": 20}}, got {}", name("params"), type_name(value)));
  for (const auto& [param, x] : value.items()) {
    const auto finite = finite_number(x);
    if (!finite)
      fail("params", fmt::format("{}.{} must be a finite number, got {}", name("params"), param,
                                 x.is_number() ? x.dump() : type_name(x)));
    params[param] = *finite;
  }
  return params;
}

queries::ModelRef Fields::model_ref(std::string_view key) const {
  const Json& value = raw(key);
  if (value.is_string()) return queries::ModelRef(value.get<std::string>());
  if (value.is_object()) return queries::ModelRef(definition_model(value, name(key)));
  fail(key, fmt::format("{} must be a model id, an inline definition such as \"lobe: c^n\" or a definition object, got {}",
                        name(key), type_name(value)));
}

queries::ModelSpec Fields::model(bool with_coef) const {
  queries::ModelSpec spec{model_ref("model"), params(), std::nullopt, std::nullopt};
  if (has("form")) spec.form = queries::form_named(text("form"), queries::Spelling::key);
  if (with_coef && has("coef")) spec.coef = number("coef");
  return spec;
}

Fields Fields::object(std::string_view key, std::set<std::string, std::less<>> known) const {
  const Json& value = raw(key);
  if (!value.is_object()) fail(key, fmt::format("{} must be an object, got {}", name(key), type_name(value)));
  return Fields(value, name(key) + ".", std::move(known));
}

}  // namespace specula::serve
