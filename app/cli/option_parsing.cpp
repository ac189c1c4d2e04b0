#include "app/cli/option_parsing.h"

#include <cmath>
#include <sstream>

#include "analysis/common/input_error.h"
#include "analysis/simulation/stepped_levels.h"

namespace oscilab::cli {

double parse_number(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value)) {
    throw InputError(option + ": \"" + text + "\" is not a number");
  }
  return value;
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || !(value > 0.0)) {
          return text + " is not a positive number";
        }
        return {};
      },
      "POSITIVE");
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, separator)) parts.push_back(part);
  return parts;
}

std::vector<double> parse_levels(const std::string& text, const std::string& option) {
  std::vector<double> levels;
  const auto range = split(text, ':');
  if (range.size() == 3) {
    const double a = parse_number(range[0], option), step = parse_number(range[1], option),
                 b = parse_number(range[2], option);
    levels = analysis::stepped_levels(a, step, b, option + ": \"" + text + "\"");
  } else if (range.size() == 1) {
    for (const auto& part : split(text, ',')) levels.push_back(parse_number(part, option));
  } else {
    throw InputError(option + ": \"" + text + "\" is neither A:STEP:B nor a list A,B,...");
  }
  return levels;
}

}  // namespace oscilab::cli
