// The cycle table's one schema: the columns docs/contracts.md §3 lists (names, units, kinds, in
// order), the rows of a campaign, and the CSV line `analyze --cycles` writes for a known cycle.
#include "analysis/pipeline/cycle_table.h"

#include <complex>

#include <gtest/gtest.h>

#include "tests/analysis/pipeline/contract_tables.h"

namespace oscilab::analysis {
namespace {

using testing::documented_columns;
using testing::schema_columns;

CycleFit known_cycle() {
  CycleFit cycle;
  cycle.start_s = 3.0;
  cycle.end_s = 3.1111111111;
  cycle.f0_n = 0.3;
  cycle.edc_j = 2.86640052e-5;
  cycle.edc_eq13_j = 2.8664e-5;
  cycle.edc_trapz_j = 2.86e-5;
  cycle.z_h = {{3e-5, -4e-5}, {1e-7, 0.0}};  // |Z1| = 5e-5 m
  cycle.lag_rad = 1.5;
  cycle.z_mean_m = 0.0236;
  cycle.z_min_m = 0.0235;
  cycle.z_max_m = 0.0237;
  return cycle;
}

TEST(CycleTable, ColumnsAreTheContractsTableInItsOrder) {
  EXPECT_EQ(schema_columns(cycle_table_columns()),
            documented_columns("### Cycle table (`analyze --cycles`)"));
}

TEST(CycleTable, EachColumnGivesTheValueOfItsKind) {
  const std::string record = "a.flac";
  const CycleFit cycle = known_cycle();
  testing::expect_values_match_kinds(cycle_table_columns(), CycleTableRow{&record, &cycle});
}

TEST(CycleTable, CsvLineOfAKnownCycleHasEachFieldInItsFormat) {
  const std::string record = "pos.flac";
  const CycleFit cycle = known_cycle();
  EXPECT_EQ(csv_line(cycle_table_columns(), CycleTableRow{&record, &cycle}),
            "pos.flac,3.000000,3.111111,0.3,2.86640052e-05,2.8664e-05,2.86e-05,5e-05,1.5,0.0236,"
            "0.0235,0.0237");
}

TEST(CycleTable, RowsFollowTheRecordsAndACycleWithoutHarmonicsHasNoAmplitude) {
  CampaignAnalysis campaign;
  campaign.records.resize(2);
  campaign.records[0].name = "one.flac";
  campaign.records[0].cycles = {known_cycle()};
  campaign.records[1].name = "two.flac";
  campaign.records[1].cycles = {known_cycle(), CycleFit{}};
  const std::vector<CycleTableRow> rows = cycle_table_rows(campaign);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(*rows[0].record, "one.flac");
  EXPECT_EQ(*rows[2].record, "two.flac");
  EXPECT_EQ(rows[2].cycle, &campaign.records[1].cycles[1]);
  const auto& z1 = cycle_table_columns()[7];
  ASSERT_EQ(std::string(z1.name), "z1_abs_m");
  EXPECT_EQ(std::get<double>(z1.value(rows[2])), 0.0);
  EXPECT_EQ(std::get<double>(z1.value(rows[0])), std::abs(std::complex<double>(3e-5, -4e-5)));
  // Without a record (the live analysis's cycles) the record is empty.
  const std::vector<CycleTableRow> live = cycle_table_rows(campaign.records[0].cycles);
  EXPECT_EQ(csv_line(cycle_table_columns(), live[0]).rfind(",3.000000,", 0), 0u);
}

}  // namespace
}  // namespace oscilab::analysis
