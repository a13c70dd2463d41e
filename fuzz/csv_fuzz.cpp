// Fuzzes the numeric CSV reader (io::parse_csv, include/specula/io/csv.h; `specula fit --data`).
// Input: the file's bytes. Properties, each a finding when broken:
//   - parse_csv() returns or throws InvalidArgument, nothing else;
//   - an error is one line that starts with the source's name;
//   - what it returns has non-empty, distinct column names, one column of values per name, every
//     column as long as the list of line numbers (≥ 1 row), line numbers strictly increasing and
//     within the file, and column_index() finds every column where it is.
#include <algorithm>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "specula/io/csv.h"

namespace {

using namespace specula;

constexpr std::string_view kSource = "fuzz.csv";

void check(std::string_view text, const io::CsvData& csv) {
  fuzz::require(!csv.columns.empty(), "parse_csv returned no columns");
  fuzz::require(csv.values.size() == csv.columns.size(), "parse_csv: columns and values differ in count");
  fuzz::require(!csv.lines.empty(), "parse_csv returned no rows");
  const auto lines_in_text = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  for (std::size_t i = 0; i < csv.lines.size(); ++i) {
    fuzz::require(csv.lines[i] >= 1 && csv.lines[i] <= lines_in_text, "parse_csv: a row's line number is outside the file");
    fuzz::require(i == 0 || csv.lines[i] > csv.lines[i - 1], "parse_csv: line numbers do not increase");
  }
  for (std::size_t c = 0; c < csv.columns.size(); ++c) {
    fuzz::require(!csv.columns[c].empty(), "parse_csv returned an empty column name");
    fuzz::require(csv.values[c].size() == csv.lines.size(), "parse_csv: a column's length differs from the row count");
    std::size_t found = 0;
    fuzz::require(fuzz::accepted("column_index", [&] { found = io::column_index(csv, csv.columns[c]); }) && found == c,
                  "column_index does not find column " + std::to_string(c + 1) + " where it is");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = fuzz::text_of(data, size);
  try {
    check(text, io::parse_csv(text, kSource));
  } catch (const InvalidArgument& e) {
    const std::string_view message = e.what();
    fuzz::require(message.starts_with(kSource), "a parse_csv error does not name the source: " + std::string(message));
    fuzz::require(message.find('\n') == std::string_view::npos, "a parse_csv error spans lines: " + std::string(message));
  } catch (const std::exception& e) {
    fuzz::finding("parse_csv: unexpected exception " + fuzz::type_name(typeid(e)) + ": " + e.what());
  }
  // Looking up a column that is not there is an InvalidArgument too.
  fuzz::accepted("column_index (absent)", [&] { (void)io::column_index(io::CsvData{}, text); });
  return 0;
}
