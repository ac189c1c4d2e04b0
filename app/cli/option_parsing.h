#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace oscilab::cli {

/// A finite number from option text; throws InputError naming the option otherwise.
double parse_number(const std::string& text, const std::string& option);

/// A CLI11 check for a positive finite number: its message names the value ("-3 is not a positive
/// number"), where CLI::PositiveNumber prints the whole double range.
CLI::Validator positive_number();

/// Splits at every separator (empty parts kept).
std::vector<std::string> split(const std::string& text, char separator);

/// Forcing levels: "A:STEP:B" (inclusive, counted by rounding so 0.2:0.1:2.7 gives 26 levels)
/// or a list "A,B,...". Throws InputError naming `option`.
std::vector<double> parse_levels(const std::string& text, const std::string& option);

}  // namespace oscilab::cli
