#include "analysis/edc/well.h"

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

// The strings are a contract: the EDC table's `well` column (docs/contracts.md §3), the JSON
// summaries and the Python module all write them.
TEST(Well, SpellsTheContractStrings) {
  EXPECT_EQ(to_string(Well::Positive), "positive");
  EXPECT_EQ(to_string(Well::Negative), "negative");
  EXPECT_EQ(to_string(Well::CrossWell), "cross-well");
  EXPECT_EQ(to_string(Well::Unknown), "unknown");
  EXPECT_EQ(to_string(Well::Unclassified), "");
}

TEST(Well, TheWellOfASideSpellsAsTheFlagDidInEveryFile) {
  // Reports, CSV files and the Python module spell a positive_well flag "positive"/"negative".
  EXPECT_EQ(to_string(well_of(true)), "positive");
  EXPECT_EQ(to_string(well_of(false)), "negative");
  static_assert(well_of(true) == Well::Positive && well_of(false) == Well::Negative);
}

TEST(Well, RoundTripsThroughItsString) {
  for (Well well :
       {Well::Positive, Well::Negative, Well::CrossWell, Well::Unknown, Well::Unclassified}) {
    EXPECT_EQ(well_from_string(to_string(well)), well) << to_string(well);
    EXPECT_EQ(parse_well(to_string(well)), well) << to_string(well);
  }
}

TEST(Well, ThrowsInputErrorNamingTheValueWhenItSpellsNoWell) {
  EXPECT_FALSE(parse_well("Positive").has_value());  // the strings are case-sensitive
  try {
    well_from_string("left");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"left\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace oscilab::analysis
