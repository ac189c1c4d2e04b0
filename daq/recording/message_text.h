#pragma once

#include <string>

// The wording the readers' messages share: names in quotes, numbers to 6 significant digits.
namespace oscilab::daq {

/// `"text"`, for names in messages.
std::string in_quotes(const std::string& text);
/// A number for messages, 6 significant digits.
std::string number_text(double value);

}  // namespace oscilab::daq
