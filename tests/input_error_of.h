#pragma once
// The error-path helper the test suites share.
#include <functional>
#include <string>

#include "analysis/common/input_error.h"

namespace oscilab::testing {

/// The message of the InputError `action` throws, or "" when it throws none.
inline std::string input_error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace oscilab::testing
