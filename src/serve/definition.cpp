#include "definition.h"

#include <algorithm>
#include <charconv>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <string_view>
#include <vector>

#include "specula/exceptions.h"
#include "specula/catalogue/model_file.h"

namespace specula::serve {
namespace {

using Json = nlohmann::json;

/// The file name parse_model_file puts in its errors, taken off again before they are answered.
constexpr std::string_view kFileName = "definition";

std::string quoted(const std::string& text) { return Json(text).dump(-1, ' ', false, Json::error_handler_t::replace); }

bool absent(const Json& object, const std::string& key) { return !object.contains(key) || object.at(key).is_null(); }

/// A JSON value as a TOML inline value of the same type, so that parse_model_file judges the types.
std::string toml_value(const Json& value, const std::string& field) {
  if (value.is_string()) return quoted(value.get<std::string>());
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  if (value.is_number()) return fmt::format("{}", value.get<double>());
  if (value.is_null()) throw InvalidField(field, fmt::format("{} holds a null", field));
  std::vector<std::string> parts;
  for (const auto& [key, item] : value.items())
    parts.push_back(value.is_array() ? toml_value(item, field) : quoted(key) + " = " + toml_value(item, field));
  return value.is_array() ? fmt::format("[{}]", fmt::join(parts, ", ")) : fmt::format("{{{}}}", fmt::join(parts, ", "));
}

/// One line of the model file: the field it holds, the key it is at ("" for a table header) and
/// the column of its value's first character.
struct Line {
  std::string field;
  std::string key;
  std::size_t value_column;
};

/// A definition as a model file of one [[model]], each key on a line of its own, so that the line
/// of an error names the field at fault.
class ModelFileText {
 public:
  ModelFileText(const Json& definition, const std::string& field) {
    add("[[model]]", {field, "", 1});
    if (absent(definition, "id")) key_value("id", "user", field);
    if (absent(definition, "name")) key_value("name", "user-defined model", field);
    for (const auto& [key, value] : definition.items()) {
      if (value.is_null() || key == "params") continue;
      if (key == "let" && value.is_array()) lets(value, field);
      else key_value(key, value, field);
    }
    if (!absent(definition, "params")) params(definition.at("params"), field + ".params");
  }

  const std::string& text() const noexcept { return text_; }
  /// The line `number` (from 1) of text(), or the [[model]] line when there is none such.
  const Line& line(std::size_t number) const noexcept {
    return number >= 1 && number <= lines_.size() ? lines_[number - 1] : lines_.front();
  }

 private:
  void add(const std::string& text, Line line) {
    text_ += text + "\n";
    lines_.push_back(std::move(line));
  }

  void key_value(const std::string& key, const Json& value, const std::string& parent) {
    const std::string field = parent + "." + key;
    const std::string assignment = quoted(key) + " = ";
    add(assignment + toml_value(value, field), {field, key, assignment.size() + 1});
  }

  void lets(const Json& list, const std::string& parent) {
    const std::string field = parent + ".let";
    add(quoted("let") + " = [", {field, "let", 1});
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string item = fmt::format("{}[{}]", field, i);
      add(toml_value(list[i], item) + ",", {item, "let", 1});
    }
    add("]", {field, "let", 1});
  }

  void params(const Json& params, const std::string& field) {
    if (!params.is_object())
      throw InvalidField(field, fmt::format("{} must be an object {{\"NAME\": {{\"default\": …, \"min\": …, \"max\": …}}}}", field));
    for (const auto& [name, param] : params.items()) {
      const std::string param_field = field + "." + name;
      if (!param.is_object())
        throw InvalidField(param_field, fmt::format("{} must be an object with default, min and max", param_field));
      add(fmt::format("[model.params.{}]", quoted(name)), {param_field, "", 1});
      for (const auto& [key, value] : param.items())
        if (!value.is_null()) key_value(key, value, param_field);
    }
  }

  std::string text_;
  std::vector<Line> lines_;
};

/// The number at the start of `text`, taken off it with the ": " after it (0 if none).
std::size_t take_number(std::string_view& text) {
  std::size_t number = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
  text.remove_prefix(static_cast<std::size_t>(end - text.data()));
  if (text.starts_with(": ")) text.remove_prefix(2);
  return number;
}

/// ".name" when `message` says a key is missing ("missing key 'name'", "lacks key 'min'").
std::string missing_key(std::string_view message) {
  for (const std::string_view says : {"missing key '", "lacks key '"}) {
    const auto at = message.find(says);
    if (at == std::string_view::npos) continue;
    const auto key = message.substr(at + says.size());
    return fmt::format(".{}", key.substr(0, key.find('\'')));  // not "." + string: GCC 12's -Wrestrict misfires on it
  }
  return "";
}

/// parse_model_file's "definition:LINE: [column N: ]MESSAGE" as the field of LINE and
/// "[column N: ]MESSAGE", the column counted in the value's string.
[[noreturn]] void fail_at_field(const ModelFileText& file, std::string_view message) {
  message.remove_prefix(std::min(message.size(), kFileName.size() + 1));
  const Line& line = file.line(take_number(message));
  std::string column;
  if (message.starts_with("column ")) {
    message.remove_prefix(7);
    column = fmt::format("column {}: ", take_number(message) - line.value_column);
  }
  if (!line.key.empty() && message.starts_with(line.key + ": ")) message.remove_prefix(line.key.size() + 2);
  throw InvalidField(line.field + missing_key(message), column + std::string(message));
}

}  // namespace

std::shared_ptr<const ModelInfo> definition_model(const Json& definition, const std::string& field) {
  const ModelFileText file(definition, field);
  std::vector<ModelInfo> models;
  try {
    models = parse_model_file(file.text(), kFileName);
  } catch (const InvalidArgument& e) {
    fail_at_field(file, e.what());
  }
  ModelInfo info = std::move(models.front());
  info.origin = {OriginKind::request, ""};
  return std::make_shared<const ModelInfo>(std::move(info));
}

}  // namespace specula::serve
