#pragma once
// Small text helpers the tests share: whole files, lines, CSV cells, words in comments.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace specula::testing {

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

/// Whether every line of generated `source` that holds `word` holds it in a comment: after "//",
/// or, where `hash_comments` (a .brdf file's header), on a line that starts with "# ".
inline bool only_in_comments(const std::string& source, std::string_view word, bool hash_comments = false) {
  for (const std::string& line : lines_of(source)) {
    const std::size_t at = line.find(word);
    if (at == std::string::npos) continue;
    const bool after_slashes = line.find("//") < at;
    if (!after_slashes && !(hash_comments && line.starts_with("# "))) return false;
  }
  return true;
}

}  // namespace specula::testing
