#pragma once
// Numeric CSV input: a header line of column names, then rows of numbers.
//   - Fields are separated by commas and trimmed of spaces and tabs.
//   - A field may be enclosed in double quotes ("" inside them is one quote); quotes keep the
//     text between them as is, commas and spaces included, and close on the same line.
//   - LF and CRLF line endings; a UTF-8 byte order mark at the start is skipped.
//   - Blank lines and comments (lines whose first non-blank character is '#') are skipped,
//     before the header too; line numbers still count them.
//   - Numbers are read by std::from_chars, all of the field: 1, -2.5, 1e-3, a leading '+', and
//     nan, inf, -inf in any case. NaN and infinities are kept: callers decide what to reject.
//     Numbers beyond the range of a double (1e400, 1e-400) are errors.
// Every error is one InvalidArgument line that names the source and, where there is one, the
// 1-based line and field, with the field's column name once the header is known:
//   data.csv: empty file, expected a header line
//   data.csv: no data rows
//   data.csv line 1, column 2: duplicate column name "n" (also column 1)
//   data.csv line 12, column 3 ("n"): expected a number, got "abc"
//   data.csv line 7, column 3 ("n"): too few fields: expected 3, found 2
//   data.csv line 8, column 4: too many fields: expected 3, found 4
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace specula::io {

/// A numeric CSV: a header line of column names, then rows of numbers.
struct CsvData {
  std::vector<std::string> columns;
  /// values[c][r]: column-major, one vector per column.
  std::vector<std::vector<double>> values;
  /// The 1-based file line of each row.
  std::vector<std::size_t> lines;
};

/// Parses CSV text. `source` names it in errors (a path or "<stdin>").
CsvData parse_csv(std::string_view text, std::string_view source);

/// Reads and parses a file; throws InvalidArgument ("cannot read '<path>': <reason>") if it cannot
/// be read. Errors in its content name the path as the source.
CsvData read_csv(const std::filesystem::path& path);

/// The index of a column by name; throws InvalidArgument naming the column and listing the
/// available ones.
std::size_t column_index(const CsvData& data, std::string_view name);

}  // namespace specula::io
