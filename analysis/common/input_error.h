#pragma once

#include <stdexcept>
#include <string>

namespace oscilab {

/// Bad input from outside the program (a file, a field, a value, an option). The message names
/// what was wrong and where, e.g. `run1.json: channels[1].unit: unknown unit "mps"`, so that it can
/// be shown to a person as it is.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace oscilab
