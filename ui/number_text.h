#pragma once

#include <cstdio>
#include <string>

namespace oscilab::ui {

/// A number as text by a printf pattern with one double, e.g. number_text("%.3f s", 12.5).
inline std::string number_text(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

}  // namespace oscilab::ui
