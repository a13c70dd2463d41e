#pragma once
// Reads the checked-in reference tables of tests/reference/ (made by make_reference.py with
// mpmath): CSV with a header line, numbers parsed with strtod.
#include <cstdlib>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "text_support.h"

namespace specula::testing {

struct ReferenceRow {
  std::map<std::string, std::string> fields;

  const std::string& text(const std::string& column) const { return fields.at(column); }
  double number(const std::string& column) const { return std::strtod(text(column).c_str(), nullptr); }
};

inline std::vector<ReferenceRow> read_reference(const std::string& name) {
  std::ifstream file(std::string(SPECULA_REFERENCE_DIR) + "/" + name);
  if (!file) throw std::runtime_error("cannot open reference table " + name);
  std::string line;
  std::getline(file, line);
  const auto header = cells_of(line);
  std::vector<ReferenceRow> rows;
  while (std::getline(file, line)) {
    if (line.empty()) continue;
    const auto cells = cells_of(line);
    ReferenceRow row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row.fields[header[i]] = cells[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace specula::testing
