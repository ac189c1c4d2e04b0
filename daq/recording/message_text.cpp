#include "daq/recording/message_text.h"

#include <cstdio>

namespace oscilab::daq {

std::string in_quotes(const std::string& text) { return "\"" + text + "\""; }

std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

}  // namespace oscilab::daq
