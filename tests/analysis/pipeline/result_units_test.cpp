// How results are stated: units per unit mass where a record has no mass, the per-unit-mass
// flag of the EDC table, and each note said once with the records it concerns.
#include "analysis/pipeline/result_units.h"

#include <gtest/gtest.h>

namespace oscilab::analysis {
namespace {

RecordAnalysis record(const std::string& name, bool per_unit_mass, std::vector<std::string> notes) {
  RecordAnalysis r;
  r.name = name;
  r.per_unit_mass = per_unit_mass;
  r.notes = std::move(notes);
  return r;
}

TEST(ResultUnits, SayPerUnitMassWhereTheMassIsUnknown) {
  CampaignAnalysis campaign;
  EXPECT_EQ(mass_basis(campaign), MassBasis::Absolute);  // nothing says otherwise
  campaign.records = {record("a", true, {}), record("b", true, {})};
  EXPECT_EQ(mass_basis(campaign), MassBasis::PerUnitMass);
  EXPECT_EQ(result_unit("N", mass_basis(campaign)), "N/kg");
  EXPECT_EQ(result_unit("mJ", mass_basis(campaign)), "mJ/kg");
  campaign.records.push_back(record("c", false, {}));
  EXPECT_EQ(mass_basis(campaign), MassBasis::Mixed);
  EXPECT_EQ(result_unit("N", MassBasis::Mixed), "N (N/kg where flagged per-unit-mass)");
  EXPECT_EQ(result_unit("J", false), "J");
}

TEST(ResultUnits, TheEdcTableFlagsALevelOfARecordWithoutMass) {
  LevelResult level;
  level.few_cycles = true;
  EXPECT_EQ(level_flags(record("a", false, {}), level), "few-cycles");
  EXPECT_EQ(level_flags(record("a", true, {}), level), "few-cycles;per-unit-mass");
  EXPECT_EQ(level_flags(record("a", true, {}), LevelResult{}), "per-unit-mass");
}

TEST(ResultUnits, EachNoteIsSaidOnceWithTheRecordsItConcerns) {
  CampaignAnalysis campaign;
  campaign.records = {record("v1.csv", true, {"no mass", "levels detected"}),
                      record("v2.csv", true, {"no mass"}),
                      record("v3.csv", true, {"no mass", "levels detected", "no mass"})};
  const std::vector<SharedNote> notes = shared_notes(campaign);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_EQ(note_text(notes[0], 3), "no mass (all 3 records)");
  EXPECT_EQ(note_text(notes[1], 3), "levels detected (v1.csv, v3.csv)");
  EXPECT_EQ(note_text(notes[1], 1), "levels detected");  // one record: no list
  SharedNote many{"gap", {}};
  for (int i = 1; i <= 8; ++i) many.records.push_back("r" + std::to_string(i));
  EXPECT_EQ(note_text(many, 20), "gap (r1, r2, r3, r4, r5, r6, and 2 more)");
}

}  // namespace
}  // namespace oscilab::analysis
