#pragma once
// The one exception type specula throws for bad input (unknown model, parameter out of range,
// malformed range or expression). The CLI turns it into one line on stderr and exit code 2.
#include <stdexcept>

namespace specula {

class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace specula
