#include "specula/io/csv.h"

#include <algorithm>
#include <charconv>
#include <fmt/format.h>
#include <unordered_map>

#include "specula/exceptions.h"
#include "specula/io/files.h"

namespace specula::io {
namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

struct Line {
  std::string_view text;  // without the line ending
  std::size_t number;     // 1-based
};

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

bool holds_content(std::string_view line) {
  const auto text = trim(line);
  return !text.empty() && text.front() != '#';
}

// The lines of `text` that are neither blank nor comments.
std::vector<Line> content_lines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t number = 1;
  for (std::size_t start = 0; start <= text.size(); ++number) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = text.substr(start, end - start);
    if (line.ends_with('\r')) line.remove_suffix(1);
    if (holds_content(line)) lines.push_back({line, number});
    start = end + 1;
  }
  return lines;
}

// A line being read, to name in errors: "source line N, column C ("name"): …".
struct Place {
  std::string_view source;
  std::size_t line;
  const std::vector<std::string>* columns;  // null while the header is read

  [[noreturn]] void fail(std::size_t field, std::string_view message) const {
    const bool named = columns && field < columns->size();
    throw InvalidArgument(fmt::format("{} line {}, column {}{}: {}", source, line, field + 1,
                                      named ? fmt::format(" (\"{}\")", (*columns)[field]) : "",
                                      message));
  }
};

void skip_blanks(std::string_view line, std::size_t& pos) {
  while (pos < line.size() && is_blank(line[pos])) ++pos;
}

// The text between the quotes that open at `pos`; leaves `pos` at the comma or end that follows.
std::string read_quoted(std::string_view line, std::size_t& pos, const Place& at,
                        std::size_t field) {
  std::string text;
  for (++pos;; ++pos) {
    if (pos == line.size()) at.fail(field, "unterminated quote");
    if (line[pos] != '"')
      text += line[pos];
    else if (line.substr(pos + 1, 1) == "\"")
      text += line[++pos];  // "" is one quote
    else
      break;
  }
  skip_blanks(line, ++pos);
  if (pos < line.size() && line[pos] != ',') at.fail(field, "text after the closing quote");
  return text;
}

// The field that starts at `pos`; leaves `pos` at the comma or end that follows.
std::string read_field(std::string_view line, std::size_t& pos, const Place& at,
                       std::size_t field) {
  skip_blanks(line, pos);
  if (pos < line.size() && line[pos] == '"') return read_quoted(line, pos, at, field);
  const std::size_t end = std::min(line.find(',', pos), line.size());
  const auto text = trim(line.substr(pos, end - pos));
  pos = end;
  return std::string(text);
}

std::vector<std::string> split_fields(std::string_view line, const Place& at) {
  std::vector<std::string> fields;
  for (std::size_t pos = 0;; ++pos) {  // ++pos steps over the comma
    fields.push_back(read_field(line, pos, at, fields.size()));
    if (pos == line.size()) return fields;
  }
}

std::vector<std::string> read_header(const Line& line, std::string_view source) {
  const Place at{source, line.number, nullptr};
  auto names = split_fields(line.text, at);
  std::unordered_map<std::string_view, std::size_t> first_column;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i].empty()) at.fail(i, "empty column name");
    const auto [first, inserted] = first_column.try_emplace(names[i], i);
    if (!inserted)
      at.fail(i, fmt::format("duplicate column name \"{}\" (also column {})", names[i], first->second + 1));
  }
  return names;
}

double parse_field_number(const std::string& text, const Place& at, std::size_t field) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (text.size() > 1 && text[0] == '+' && text[1] != '-') ++first;  // "+1", not "+-1"
  double value = 0;
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range && end == last)
    at.fail(field, fmt::format("the number \"{}\" is out of the range of a double", text));
  if (ec != std::errc() || end != last)
    at.fail(field, fmt::format("expected a number, got \"{}\"", text));
  return value;
}

void check_field_count(std::size_t found, std::size_t expected, const Place& at) {
  if (found < expected)
    at.fail(found, fmt::format("too few fields: expected {}, found {}", expected, found));
  if (found > expected)
    at.fail(expected, fmt::format("too many fields: expected {}, found {}", expected, found));
}

void append_row(CsvData& data, const Line& line, std::string_view source) {
  const Place at{source, line.number, &data.columns};
  const auto fields = split_fields(line.text, at);
  check_field_count(fields.size(), data.columns.size(), at);
  for (std::size_t c = 0; c < fields.size(); ++c)
    data.values[c].push_back(parse_field_number(fields[c], at, c));
  data.lines.push_back(line.number);
}

}  // namespace

CsvData parse_csv(std::string_view text, std::string_view source) {
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  const auto lines = content_lines(text);
  if (lines.empty())
    throw InvalidArgument(fmt::format("{}: empty file, expected a header line", source));
  CsvData data;
  data.columns = read_header(lines.front(), source);
  data.values.resize(data.columns.size());
  for (std::size_t i = 1; i < lines.size(); ++i) append_row(data, lines[i], source);
  if (data.lines.empty()) throw InvalidArgument(fmt::format("{}: no data rows", source));
  return data;
}

CsvData read_csv(const std::filesystem::path& path) { return parse_csv(read_file(path), path.string()); }

std::size_t column_index(const CsvData& data, std::string_view name) {
  const auto it = std::find(data.columns.begin(), data.columns.end(), name);
  if (it != data.columns.end()) return static_cast<std::size_t>(it - data.columns.begin());
  std::string available;
  for (const auto& column : data.columns)
    available += fmt::format("{}\"{}\"", available.empty() ? "" : ", ", column);
  throw InvalidArgument(fmt::format("no column \"{}\"; the columns are {}", name, available));
}

}  // namespace specula::io
