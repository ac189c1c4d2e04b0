#include "analysis/edc/well.h"

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

constexpr Well kWells[] = {Well::Positive, Well::Negative, Well::CrossWell, Well::Unknown,
                           Well::Unclassified};

}  // namespace

std::string to_string(Well well) {
  switch (well) {
    case Well::Positive:
      return "positive";
    case Well::Negative:
      return "negative";
    case Well::CrossWell:
      return "cross-well";
    case Well::Unknown:
      return "unknown";
    case Well::Unclassified:
      return "";
  }
  return "unknown";
}

std::optional<Well> parse_well(std::string_view text) {
  for (Well well : kWells) {
    if (text == to_string(well)) return well;
  }
  return std::nullopt;
}

Well well_from_string(const std::string& text) {
  const std::optional<Well> well = parse_well(text);
  if (!well) {
    throw InputError("well: \"" + text +
                     "\" is not positive, negative, cross-well, unknown or empty");
  }
  return *well;
}

}  // namespace oscilab::analysis
