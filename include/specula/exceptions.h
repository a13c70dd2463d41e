#pragma once
// The one exception type specula throws for bad input (unknown model, parameter out of range,
// malformed range or expression). The CLI turns it into one line on stderr and exit code 2.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace specula {

class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Bad input in one named field of a request: `field` is its key ("theta_i", "params", "n"),
/// whatever the interface that spelled it in the message (the CLI's --theta-i, the server's
/// JSON key). The server answers it with {"error": message, "field": field}.
class InvalidField : public InvalidArgument {
 public:
  InvalidField(std::string field, const std::string& message)
      : InvalidArgument(message), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

/// `message` as exactly one line of text: control characters (a newline or tab inside a user's
/// argument echoed back, an escape sequence) are written as C escapes (\n, \t, \x1b), so that
/// an error printed by the CLI is always one line, whatever the input it quotes.
inline std::string one_line(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (byte < 0x20 || byte == 0x7f) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else out += c;
  }
  return out;
}

}  // namespace specula
