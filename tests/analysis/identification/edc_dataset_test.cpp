#include "analysis/identification/edc_dataset.h"

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::analysis {
namespace {

LevelResult level(Well well, double f0, double edc, int cycles) {
  LevelResult r;
  r.well = well;
  r.f0_n = f0;
  r.edc_mean_j = edc;
  r.edc_std_j = 0.1 * edc;
  r.cycles = cycles;
  return r;
}

RecordAnalysis record(const std::string& name, double freq_hz, std::vector<LevelResult> levels) {
  RecordAnalysis r;
  r.name = name;
  r.stepped_sine = true;
  r.setup.excitation_freq_hz = freq_hz;
  r.levels = std::move(levels);
  return r;
}

TEST(EdcDataset, KeepsUsableLevelsPerWellAndListsTheRest) {
  CampaignAnalysis campaign;
  LevelResult doubled = level(Well::Positive, 3.0, 0.02, 40);
  doubled.period1 = false;
  LevelResult crossing = level(Well::CrossWell, 3.2, 0.05, 40);
  crossing.cross_well = true;
  campaign.records.push_back(record("up.flac", 9.0,
                                    {level(Well::Positive, 0.4, 2e-4, 80),
                                     level(Well::Positive, 0.2, 1e-4, 80), doubled, crossing}));
  campaign.records.push_back(record("down.flac", 9.0001, {level(Well::Negative, 0.5, 3e-4, 70)}));
  RecordAnalysis random;
  random.name = "random.flac";
  campaign.records.push_back(random);

  const EdcDataset data = edc_dataset(campaign);
  ASSERT_EQ(data.groups.size(), 2u);  // 9 Hz and 9.0001 Hz share a frequency (0.1 %)
  const EdcGroup* plus = data.group(true);
  ASSERT_NE(plus, nullptr);
  ASSERT_EQ(plus->levels.size(), 2u);
  EXPECT_EQ(plus->levels[0].f0_n, 0.2);  // sorted by f0
  EXPECT_EQ(plus->levels[1].record, "up.flac");
  EXPECT_EQ(data.group(false)->levels.size(), 1u);
  ASSERT_EQ(data.excluded.size(), 3u);
  EXPECT_NE(data.excluded[0].find("not-period-1"), std::string::npos) << data.excluded[0];
  EXPECT_NE(data.excluded[1].find("cross-well"), std::string::npos) << data.excluded[1];
  EXPECT_NE(data.excluded[2].find("random.flac"), std::string::npos) << data.excluded[2];
}

TEST(EdcDataset, MergesTheSameLevelFromTwoRecordsByCycles) {
  CampaignAnalysis campaign;
  campaign.records.push_back(record("a.flac", 9.0, {level(Well::Positive, 1.0, 0.010, 30)}));
  campaign.records.push_back(record("b.flac", 9.0, {level(Well::Positive, 1.0, 0.013, 10)}));
  const EdcDataset data = edc_dataset(campaign);
  ASSERT_EQ(data.level_count(), 1);
  const MeasuredLevel& m = data.groups[0].levels[0];
  EXPECT_NEAR(m.edc_j, (30 * 0.010 + 10 * 0.013) / 40.0, 1e-15);
  EXPECT_EQ(m.cycles, 40);
  EXPECT_EQ(m.record, "a.flac+b.flac");
}

TEST(EdcDataset, SigmaOfMeanIsTheStandardErrorWithTheNoiseFloorBelow) {
  MeasuredLevel m;
  m.edc_std_j = 0.4;
  m.cycles = 16;
  EXPECT_DOUBLE_EQ(m.sigma_of_mean_j(), 0.1);
  m.noise_floor_j = 0.2;
  EXPECT_DOUBLE_EQ(m.sigma_of_mean_j(), 0.2);
}

TEST(EdcDataset, ThrowsNamingTheRecordsWhenNothingIsUsable) {
  CampaignAnalysis campaign;
  LevelResult crossing = level(Well::CrossWell, 3.2, 0.05, 40);
  crossing.cross_well = true;
  campaign.records.push_back(record("only.flac", 9.0, {crossing}));
  try {
    edc_dataset(campaign);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("only.flac"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace oscilab::analysis
