#include "specula/io/table.h"

#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "specula/exceptions.h"

namespace specula::io {

std::string format_number(double v, std::optional<int> decimals) {
  if (decimals) return fmt::format("{:.{}f}", v, *decimals);
  return fmt::format("{}", v);
}

std::string to_csv(const Table& table, std::optional<int> decimals) {
  std::string out = fmt::format("{}\n", fmt::join(table.columns, ","));
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i) out += ',';
      out += format_number(row[i], i < table.key_columns ? std::nullopt : decimals);
    }
    out += '\n';
  }
  return out;
}

std::string to_json(const Table& table, std::optional<int> decimals) {
  auto number = [&](double v, bool key) -> nlohmann::json {
    if (!std::isfinite(v)) return nullptr;
    if (!decimals || key) return v;
    return std::stod(format_number(v, decimals));
  };
  nlohmann::ordered_json out;
  for (const auto& [key, value] : table.meta) out[key] = value;
  out["columns"] = table.columns;
  out["rows"] = nlohmann::ordered_json::array();
  for (const auto& row : table.rows) {
    nlohmann::ordered_json object;
    for (std::size_t i = 0; i < row.size() && i < table.columns.size(); ++i)
      object[table.columns[i]] = number(row[i], i < table.key_columns);
    out["rows"].push_back(std::move(object));
  }
  return out.dump(2) + "\n";
}

}  // namespace specula::io
