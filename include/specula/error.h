#pragma once
// The one exception type specula throws for bad input (unknown model, parameter out of range,
// malformed range or expression). The CLI turns it into one line on stderr and exit code 2.
#include <stdexcept>
#include <string>

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

}  // namespace specula
