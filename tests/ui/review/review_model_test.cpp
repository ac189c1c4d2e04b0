// The Qt-free logic of the record review: level rows, level loops and their area, the
// excitation force, the samples behind the restoring-force slices and the K(z) text.
#include "ui/review/review_model.h"

#include "analysis/rfs/motion_signals.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/model/reference_models.h"
#include "analysis/rfs/restoring_force_slices.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::ui {
namespace {

using analysis::LevelResult;

LevelResult level(analysis::Well well, double f0_n, double edc_mean_j, double edc_std_j,
                  int cycles) {
  LevelResult result;
  result.well = well;
  result.f0_n = f0_n;
  result.edc_mean_j = edc_mean_j;
  result.edc_std_j = edc_std_j;
  result.cycles = cycles;
  return result;
}

TEST(LevelRows, OneRowPerLevelWithTheLevelsNumbersAndFlags) {
  std::vector<LevelResult> levels = {level(analysis::Well::Positive, 0.2, 1.5e-4, 2e-6, 70),
                                     level(analysis::Well::CrossWell, 2.6, 2.1e-2, 4e-3, 60),
                                     level(analysis::Well::Negative, 0.3, 3.0e-4, 5e-6, 3)};
  levels[1].cross_well = true;
  levels[1].period1 = false;
  levels[2].few_cycles = true;
  const std::vector<LevelRow> rows = level_rows(4, "run1.flac", levels);
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].key, (LevelKey{4, int(i)}));
    EXPECT_EQ(rows[i].record, "run1.flac");
    EXPECT_EQ(rows[i].well, levels[i].well);
    EXPECT_EQ(rows[i].f0_n, levels[i].f0_n);
    EXPECT_EQ(rows[i].edc_mean_j, levels[i].edc_mean_j);
    EXPECT_EQ(rows[i].edc_std_j, levels[i].edc_std_j);
    EXPECT_EQ(rows[i].cycles, levels[i].cycles);
  }
  EXPECT_EQ(rows[0].flags, "");
  EXPECT_EQ(rows[1].flags, "not-period-1;cross-well");  // LevelResult::flags()
  EXPECT_EQ(rows[2].flags, "few-cycles");
  // Without mass_kg the energies are per unit mass: the row says so.
  EXPECT_EQ(level_rows(0, "r", levels, true)[0].flags, "per-unit-mass");
  EXPECT_EQ(level_rows(0, "r", levels, true)[2].flags, "few-cycles;per-unit-mass");
}

TEST(LevelRows, CampaignRowsGoRecordByRecordAndFindTheirLevel) {
  analysis::CampaignAnalysis campaign;
  campaign.records.resize(2);
  campaign.records[0].name = "pos.flac";
  campaign.records[0].levels = {level(analysis::Well::Positive, 0.2, 1e-4, 0, 10),
                                level(analysis::Well::Positive, 0.3, 2e-4, 0, 10)};
  campaign.records[1].name = "neg.flac";
  campaign.records[1].levels = {level(analysis::Well::Negative, 0.2, 1.1e-4, 0, 10)};
  const std::vector<LevelRow> rows = level_rows(campaign);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].key, (LevelKey{0, 1}));
  EXPECT_EQ(rows[2].key, (LevelKey{1, 0}));
  EXPECT_EQ(rows[2].record, "neg.flac");
  for (const LevelRow& row : rows) {
    const LevelResult* found = find_level(campaign, row.key);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->f0_n, row.f0_n);
  }
  EXPECT_EQ(find_level(campaign, {1, 1}), nullptr);
  EXPECT_EQ(find_level(campaign, {2, 0}), nullptr);
  EXPECT_EQ(find_level(campaign, {-1, 0}), nullptr);
}

TEST(LevelView, CursorInTheMiddleAndWindowAroundTheSteadyCycles) {
  LevelResult l;
  l.start_s = 10.0;
  l.end_s = 20.0;
  EXPECT_DOUBLE_EQ(level_cursor_time_s(l), 15.0);
  const TimeWindow window = level_time_window(l, 0.1);
  EXPECT_DOUBLE_EQ(window.start_s, 9.0);
  EXPECT_DOUBLE_EQ(window.end_s, 21.0);
}

// z = Z sin(ωt − φ) lagging f = F sin(ωt): each cycle dissipates π F Z sin φ (eq. (13), exact for
// a sinusoid). Sampled at 64 points a period, the trapezoidal loop sum over whole periods is
// exactly that times sinc(ωh) = sin(ωh)/(ωh) (the sum of a sampled sinusoid product).
TEST(LevelLoop, HoldsTheSteadySamplesAndItsAreaIsTheEnergyPerCycle) {
  constexpr double kFreqHz = 9.0, kRateHz = 64 * kFreqHz;
  constexpr double kF = 1.3, kZ = 2e-3, kPhi = 0.4;  // N, m, rad
  const double omega = 2 * std::numbers::pi * kFreqHz;
  const Eigen::Index n = Eigen::Index(20 * kRateHz);  // 20 s
  analysis::MotionSignals motion;
  motion.t_s = Eigen::VectorXd::LinSpaced(n, 0.0, double(n - 1) / kRateHz);
  motion.z_m = (omega * motion.t_s.array() - kPhi).sin() * kZ;
  motion.z_dot_m_s = (omega * motion.t_s.array() - kPhi).cos() * kZ * omega;
  motion.restoring_force_n = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd f_n = (omega * motion.t_s.array()).sin() * kF;

  LevelResult l = level(analysis::Well::Positive, kF, 0, 0, 45);
  l.start_s = 5.0;  // 45 cycles of 1/9 s: [5, 10]
  l.end_s = 5.0 + 45 / kFreqHz;
  const LevelLoop loop = level_loop(motion, f_n, l);
  EXPECT_EQ(loop.well, analysis::Well::Positive);
  EXPECT_EQ(loop.cycles, 45);
  ASSERT_EQ(loop.z_m.size(), std::size_t(45 * 64 + 1));  // both ends are sample times
  EXPECT_DOUBLE_EQ(loop.t_s.front(), 5.0);
  EXPECT_NEAR(loop.t_s.back(), l.end_s, 1e-12);
  const double a = omega / kRateHz;
  const double exact_j = 45 * std::numbers::pi * kF * kZ * std::sin(kPhi);
  // Round-off only: 2881 terms of size ~1e-4 J.
  EXPECT_NEAR(loop_area_j(loop.z_m, loop.f_n) / exact_j, std::sin(a) / a, 1e-12);

  // Samples the analysis left out (non-finite R) are not part of the loop.
  motion.restoring_force_n.segment(Eigen::Index(6.0 * kRateHz), 10).setConstant(NAN);
  EXPECT_EQ(level_loop(motion, f_n, l).z_m.size(), loop.z_m.size() - 10);
}

// A level's loop made from a window of its record (what the review draws, the motion not kept)
// against the loop of the whole record's motion and excitation force, the second method: the
// same samples, z and f equal to the spans' accuracy (motion_spans.h: 6e-6 of z's range).
TEST(LevelLoop, FromItsWindowIsTheLoopOfTheWholeRecordsMotion) {
  analysis::SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.5, 2.5};
  daq::RigSpec spec;
  spec.seed = 5;
  const daq::Recording recording =
      daq::record_stepped_sine(analysis::paper_model(), schedule, spec).recording;
  const auto opened = std::make_shared<const daq::OpenedRecording>(daq::hold_recording(recording));
  const ReviewAnalysis review = analyze_review({opened}, analysis::PipelineSettings());
  ASSERT_EQ(review.campaign.status, JobStatus::Ok)
      << (review.errors.empty() ? "" : review.errors[0]);
  EXPECT_EQ(review.campaign.records[0].motion.t_s.size(), 0);  // not kept
  const analysis::MeasurementChannels channels = daq::measurement_channels(recording);
  const analysis::PipelineSettings& settings = review.campaign.settings;
  const analysis::MotionSignals motion =
      analysis::motion_signals(channels, settings, channels.mass_kg.value_or(1.0));
  const Eigen::VectorXd force_n = analysis::excitation_force(channels, settings);
  const double z_range_m = motion.z_m.maxCoeff() - motion.z_m.minCoeff();
  const double f_range_n = force_n.maxCoeff() - force_n.minCoeff();
  ASSERT_EQ(review.campaign.records[0].levels.size(), 3u);
  for (const LevelResult& l : review.campaign.records[0].levels) {
    const LevelLoop windowed = level_loop(*opened, settings, l);
    const LevelLoop whole = level_loop(motion, force_n, l);
    ASSERT_GT(whole.t_s.size(), 1000u);
    ASSERT_EQ(windowed.t_s, whole.t_s);
    EXPECT_EQ(windowed.cycles, whole.cycles);
    double z_error = 0.0, f_error = 0.0;
    for (std::size_t i = 0; i < whole.t_s.size(); ++i) {
      z_error = std::max(z_error, std::abs(windowed.z_m[i] - whole.z_m[i]));
      f_error = std::max(f_error, std::abs(windowed.f_n[i] - whole.f_n[i]));
    }
    EXPECT_LT(z_error, 1e-5 * z_range_m) << "level at " << l.f0_n << " N";
    EXPECT_LT(f_error, 1e-5 * f_range_n) << "level at " << l.f0_n << " N";
  }
  // The slices' points came from one more pass over the same motion.
  EXPECT_GT(review.slice_points.stiffness.selected, 1000u);
  EXPECT_EQ(review.slice_points.damping.size(), review.campaign.damping.size());
}

// f = −m b̈ (eq. (1)) of a 9 Hz table motion, measured as acceleration or as displacement, away
// from the record's ends (the even extension kinks there and the low-pass rings over a few
// periods of 60 Hz).
TEST(ExcitationForce, IsMinusMassTimesTableAccelerationWhateverTheBaseQuantity) {
  constexpr double kRateHz = 512.0, kFreqHz = 9.0, kMassKg = 0.26, kAcc = 2.5;  // m/s²
  const double omega = 2 * std::numbers::pi * kFreqHz;
  const Eigen::Index n = Eigen::Index(10 * kRateHz);
  const Eigen::ArrayXd t = Eigen::ArrayXd::LinSpaced(n, 0.0, double(n - 1) / kRateHz);
  analysis::MeasurementChannels channels;
  channels.sample_rate_hz = kRateHz;
  channels.mass_kg = kMassKg;
  channels.mass = Eigen::VectorXd::Zero(n);
  channels.base = (omega * t).sin() * kAcc;
  channels.base_quantity = analysis::MotionQuantity::Acceleration;
  const analysis::PipelineSettings settings;
  const Eigen::VectorXd from_acc = analysis::excitation_force(channels, settings);
  channels.base = (omega * t).sin() * (-kAcc / (omega * omega));  // b with b̈ = 2.5 sin ωt
  channels.base_quantity = analysis::MotionQuantity::Displacement;
  const Eigen::VectorXd from_disp = analysis::excitation_force(channels, settings);
  double worst_acc = 0.0, worst_disp = 0.0;
  for (Eigen::Index i = Eigen::Index(kRateHz); i < n - Eigen::Index(kRateHz); ++i) {
    const double expected_n = -kMassKg * kAcc * std::sin(omega * t[i]);
    worst_acc = std::max(worst_acc, std::abs(from_acc[i] - expected_n));
    worst_disp = std::max(worst_disp, std::abs(from_disp[i] - expected_n));
  }
  // 0.65 N amplitude; 9 Hz is in the pass band (window 1), so what is left is the ringing of
  // the end kinks, decayed 1 s in: below 1e-4 of the amplitude.
  EXPECT_LT(worst_acc, 0.65e-4);
  EXPECT_LT(worst_disp, 0.65e-4);
  // Without mass_kg: per unit mass.
  channels.mass_kg.reset();
  EXPECT_NEAR(analysis::excitation_force(channels, settings)[n / 2], from_disp[n / 2] / kMassKg,
              1e-12);
}

// A Duffing-like record: R = k1 z + k3 z³ + c ż over a slow amplitude sweep.
analysis::CampaignAnalysis synthetic_campaign() {
  constexpr double kRateHz = 512.0, kFreqHz = 9.0;
  const double omega = 2 * std::numbers::pi * kFreqHz;
  const Eigen::Index n = Eigen::Index(60 * kRateHz);
  analysis::CampaignAnalysis campaign;
  campaign.records.resize(1);
  analysis::MotionSignals& m = campaign.records[0].motion;
  m.t_s = Eigen::VectorXd::LinSpaced(n, 0.0, double(n - 1) / kRateHz);
  const Eigen::ArrayXd amplitude = 1e-3 + 4e-3 * m.t_s.array() / m.t_s[n - 1];
  m.z_m = (amplitude * (omega * m.t_s.array()).sin()).matrix();
  m.z_dot_m_s = (amplitude * omega * (omega * m.t_s.array()).cos()).matrix();
  m.restoring_force_n =
      (-120.0 * m.z_m.array() + 4e6 * m.z_m.array().cube() + 0.5 * m.z_dot_m_s.array()).matrix();
  const std::vector<const analysis::MotionSignals*> records = {&m};
  campaign.stiffness = analysis::stiffness_slice(records, campaign.settings);
  campaign.damping.push_back(
      analysis::damping_slice(records, *campaign.stiffness, 2e-3, campaign.settings));
  return campaign;
}

TEST(SlicePoints, StiffnessPointsAreTheSamplesTheCoreFitted) {
  const analysis::CampaignAnalysis campaign = synthetic_campaign();
  const analysis::MotionPass pass = analysis::campaign_motion_pass(campaign, {});
  const ScatterPoints all = slice_points(pass, campaign, 0, 0).stiffness;
  // The same samples: the same count, and a cubic through them gives the core's coefficients.
  ASSERT_EQ(Eigen::Index(all.selected), campaign.stiffness->fit.samples);
  const analysis::PolynomialFit refit = analysis::fit_polynomial(
      Eigen::Map<const Eigen::VectorXd>(all.x.data(), Eigen::Index(all.x.size())),
      Eigen::Map<const Eigen::VectorXd>(all.y.data(), Eigen::Index(all.y.size())), 3);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(refit.coefficients[i], campaign.stiffness->fit.coefficients[i],
                1e-9 * std::abs(campaign.stiffness->fit.coefficients[i]) + 1e-12);
  }
  // Thinning keeps at most the count asked for, evenly, and reports how many were selected.
  const ScatterPoints thin = slice_points(pass, campaign, 100, 0).stiffness;
  EXPECT_LE(thin.x.size(), 100u);
  EXPECT_GT(thin.x.size(), 50u);
  EXPECT_EQ(thin.selected, all.selected);
  // By an even stride, the least power of two that leaves at most 100 (the stride is doubled
  // while the points stream in): the k-th kept is the (k·stride)-th selected.
  std::size_t stride = 1;
  while ((all.x.size() + stride - 1) / stride > 100) stride *= 2;
  ASSERT_EQ(thin.x.size(), (all.x.size() + stride - 1) / stride);
  for (std::size_t k = 0; k < thin.x.size(); ++k) {
    ASSERT_EQ(thin.x[k], all.x[k * stride]) << k;
    ASSERT_EQ(thin.y[k], all.y[k * stride]) << k;
  }
}

TEST(SlicePoints, DampingPointsAreTheSamplesTheCoreBinned) {
  const analysis::CampaignAnalysis campaign = synthetic_campaign();
  const analysis::DampingSlice& slice = campaign.damping[0];
  ASSERT_EQ(int(slice.bins.size()), campaign.settings.damping_bins);  // all bins filled
  const analysis::MotionPass pass = analysis::campaign_motion_pass(campaign, {});
  const ScatterPoints points = slice_points(pass, campaign, 0, 0).damping.at(0);
  const double width = (slice.bins.back().x - slice.bins.front().x) / double(slice.bins.size() - 1);
  const double lo = slice.bins.front().x - 0.5 * width, hi = slice.bins.back().x + 0.5 * width;
  // Over the binned range the same samples: the same count and the same sum of D.
  int binned = 0;
  double binned_sum_n = 0.0;
  for (const analysis::SliceBin& bin : slice.bins) {
    binned += bin.samples;
    binned_sum_n += bin.samples * bin.force_n;
  }
  int inside = 0;
  double inside_sum_n = 0.0, scale_n = 0.0;
  for (std::size_t i = 0; i < points.x.size(); ++i) {
    scale_n = std::max(scale_n, std::abs(points.y[i]));
    if (points.x[i] >= lo - 1e-9 * width && points.x[i] < hi + 1e-9 * width) {
      ++inside;
      inside_sum_n += points.y[i];
    }
  }
  EXPECT_EQ(inside, binned);
  EXPECT_NEAR(inside_sum_n, binned_sum_n, 1e-12 * scale_n * inside);  // summation order only
  // Bin by bin: a sample on an inner edge may fall either side under round-off.
  for (const analysis::SliceBin& bin : slice.bins) {
    int count = 0;
    for (double x : points.x) count += std::abs(x - bin.x) < 0.5 * width ? 1 : 0;
    EXPECT_LE(std::abs(count - bin.samples), 1) << "bin at " << bin.x;
  }
}

TEST(StiffnessFitText, UsesThePapersSignsAndUnits) {
  EXPECT_EQ(value_with_error(204100.0, 12.0), "2.041e+05 \u00b1 12");
  analysis::StiffnessSlice slice;
  slice.fit.coefficients = Eigen::Vector4d(0.01, -50.0, 3.0, 2.0e5);
  slice.fit.std_errors = Eigen::Vector4d(0.001, 0.5, 0.25, 1.0e3);
  slice.fit.residual_rms = 0.0123;
  slice.fit.samples = 4321;
  const std::string text = stiffness_fit_text(slice);
  // Eq. (2): K = k3 z³ + k2 z² − k1 z + k0, so k1 = −c1 = 50.
  EXPECT_NE(text.find("k\u2083 = 2e+05 \u00b1 1e+03 N/m\u00b3"), std::string::npos) << text;
  EXPECT_NE(text.find("k\u2082 = 3 \u00b1 0.25 N/m\u00b2"), std::string::npos) << text;
  EXPECT_NE(text.find("k\u2081 = 50 \u00b1 0.5 N/m"), std::string::npos) << text;
  EXPECT_NE(text.find("k\u2080 = 0.01 \u00b1 0.001 N"), std::string::npos) << text;
  EXPECT_NE(text.find("4321 samples"), std::string::npos) << text;
}

}  // namespace
}  // namespace oscilab::ui
