// The EDC table's one schema: the columns docs/contracts.md §3 lists (names, units, kinds, in
// order), the rows of a campaign, and the CSV line `analyze --edc` writes for a known level.
#include "analysis/pipeline/edc_table.h"

#include <gtest/gtest.h>

#include "tests/analysis/pipeline/contract_tables.h"

namespace oscilab::analysis {
namespace {

using testing::documented_columns;
using testing::schema_columns;

LevelResult known_level() {
  LevelResult level;
  level.well = Well::Negative;
  level.f0_n = 0.25;
  level.edc_mean_j = 1.234567891234e-4;
  level.edc_std_j = 2.5e-6;
  level.cycles = 84;
  level.edc_noise_floor_j = 3e-8;
  level.edc_eq13_mean_j = 1.2e-4;
  level.edc_trapz_mean_j = 1.1e-4;
  level.z1_abs_m = 0.0075;
  level.lag_rad = 2.5;
  level.z_mean_m = -0.0303;
  level.start_s = 13.0;
  level.end_s = 22.4444444444;
  level.transient_cycles = 2;
  level.period1_change = 0.0123;
  return level;
}

TEST(EdcTable, ColumnsAreTheContractsTableInItsOrder) {
  EXPECT_EQ(schema_columns(edc_table_columns()),
            documented_columns("### EDC table (`analyze --edc`)"));
}

TEST(EdcTable, HeaderBeginsWithTheFiveColumnsScriptsRelyOn) {
  EXPECT_EQ(csv_header(edc_table_columns()).rfind("well,f0_n,edc_mean_j,edc_std_j,cycles,", 0), 0u);
}

TEST(EdcTable, EachColumnGivesTheValueOfItsKind) {
  testing::expect_values_match_kinds(edc_table_columns(), EdcTableRow{"a", known_level(), ""});
}

TEST(EdcTable, CsvLineOfAKnownLevelHasEachFieldInItsFormat) {
  // The digits analyze --edc has always written: %.9g for the EDC and the motion, %.6g for
  // amplitudes, scatter and ratios, microseconds for times.
  const EdcTableRow row{"neg.flac", known_level(), ""};
  EXPECT_EQ(csv_line(edc_table_columns(), row),
            "negative,0.25,0.000123456789,2.5e-06,84,neg.flac,3e-08,0.00012,0.00011,0.0075,2.5,"
            "-0.0303,13.000000,22.444444,2,0.0123,1,");
}

TEST(EdcTable, RowsFollowTheRecordsAndFlagALevelWithoutMass) {
  CampaignAnalysis campaign;
  campaign.records.resize(2);
  campaign.records[0].name = "pos.flac";
  campaign.records[0].levels = {known_level(), known_level()};
  campaign.records[1].name = "nomass.flac";
  campaign.records[1].per_unit_mass = true;
  campaign.records[1].levels = {known_level()};
  campaign.records[1].levels[0].cross_well = true;
  const std::vector<EdcTableRow> rows = edc_table_rows(campaign);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].record, "pos.flac");
  EXPECT_EQ(rows[2].record, "nomass.flac");
  EXPECT_EQ(rows[0].flags, "");
  EXPECT_EQ(rows[2].flags, "cross-well;per-unit-mass");
  const std::string line = csv_line(edc_table_columns(), rows[2]);
  EXPECT_EQ(line.substr(line.size() - std::string(",0,cross-well;per-unit-mass").size()),
            ",0,cross-well;per-unit-mass");  // not usable: crosses the wells
}

}  // namespace
}  // namespace oscilab::analysis
