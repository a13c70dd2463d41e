#pragma once
// A table of numbers with named columns, written as CSV or JSON (files: specula/io/files.h).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace specula::io {

/// Shortest round-trip text of v (full double precision), or `decimals` fixed decimals.
std::string format_number(double v, std::optional<int> decimals = std::nullopt);

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  /// Context printed in JSON before the rows (model, form, method…); CSV leaves it out.
  std::vector<std::pair<std::string, std::string>> meta;
  /// The leading columns that hold inputs (n, cos, θ): never rounded.
  std::size_t key_columns = 1;
};

/// Header line, then one line per row.
std::string to_csv(const Table& table, std::optional<int> decimals = std::nullopt);
/// {meta…, "columns": [...], "rows": [{column: value}, …]}; non-finite values become null.
std::string to_json(const Table& table, std::optional<int> decimals = std::nullopt);

}  // namespace specula::io
