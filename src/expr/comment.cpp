// Any text as the body of a one-line comment (specula/expr/comment.h).
#include "specula/expr/comment.h"

#include <utility>

namespace specula::expr {
namespace {

/// docs/math.md's symbols spelled in ASCII.
std::string spelled_out(std::string text) {
  static const std::pair<std::string_view, std::string_view> spelled[] = {
      {"π", "pi"}, {"θ", "theta"}, {"δ", "d"}, {"α", "alpha"}, {"ρ", "rho"}, {"·", "."}, {"½", "1/2 "}, {"²", "^2"},
      {"³", "^3"}, {"⁴", "^4"}, {"−", "-"}, {"√", "sqrt"}, {"₁", "1"}, {"₂", "2"}, {"₀", "0"},
      {"–", "-"}, {"≈", "~"}, {"ˢ", "s"}, {"é", "e"}, {"ü", "u"}, {"ö", "o"}, {"≤", "<="}, {"∈", "in"}, {"§", ""}, {"→", "->"}, {"×", "x"}};
  for (const auto& [from, to] : spelled)
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
      text.replace(at, from.size(), to);
  return text;
}

/// Control characters as spaces, other non-ASCII characters as one '?' each (a UTF-8 sequence's
/// continuation bytes, 10xxxxxx, dropped).
std::string printable_ascii(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte < 0x20 || byte == 0x7f) out += ' ';
    else if (byte < 0x80) out += ch;
    else if ((byte & 0xc0) != 0x80) out += '?';
  }
  return out;
}

/// Whether `second` right after `first` opens or closes a block comment, or begins a trigraph.
bool forms_token(char first, char second) {
  return (first == '/' && second == '*') || (first == '*' && second == '/') || (first == '?' && second == '?');
}

}  // namespace

std::string comment_text(std::string_view text) {
  std::string flat = printable_ascii(spelled_out(std::string(text)));
  flat.erase(flat.find_last_not_of(' ') + 1);
  if (flat.ends_with('\\')) flat.back() = '/';
  std::string out;
  for (const char ch : flat) {
    if (!out.empty() && forms_token(out.back(), ch)) out += ' ';
    out += ch;
  }
  return out;
}

}  // namespace specula::expr
