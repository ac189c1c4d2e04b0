#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace oscilab::analysis {

/// The well a level or a response belongs to: around z₊* or z₋* (§2), crossing between them, or
/// not known (a velocity channel gives no mean position and no hint was given).
enum class Well {
  Positive,
  Negative,
  CrossWell,
  Unknown,
  Unclassified,  // a level without steady cycles (it never settled): no motion to judge
};

/// The well of a response around the positive (z₊*) or the negative (z₋*) equilibrium, for the
/// many places that hold the side as a flag (`positive_well`).
constexpr Well well_of(bool positive) { return positive ? Well::Positive : Well::Negative; }

/// The well as every file, report and the Python module spell it: "positive", "negative",
/// "cross-well", "unknown", and "" for Unclassified.
std::string to_string(Well well);

/// The well `text` spells (the inverse of to_string), or nothing when it spells none.
std::optional<Well> parse_well(std::string_view text);

/// The well `text` spells (the inverse of to_string); throws InputError naming `text` otherwise.
Well well_from_string(const std::string& text);

}  // namespace oscilab::analysis
