// The live restoring-force slices: against a known surface R = K(z) + c ż, and against the
// offline stiffness slice of the same record.
#include "analysis/rfs/streaming_slices.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <numbers>

#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "analysis/rfs/restoring_force_slices.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/rig/virtual_rig.h"

namespace oscilab::analysis {
namespace {

// Samples of a known motion: z = z0 + A sin ωt, R = K(z) + c ż, one per sample.
struct Motion {
  std::vector<double> t_s, z_m, z_dot_m_s, restoring_force_n;
};

double stiffness(double z) { return 7.35e5 * z * z * z + 1.56e3 * z * z - 550 * z + 2.4; }

Motion motion(double t0, double t1, double rate, double z0, double a, double nu, double c) {
  Motion m;
  const double w = 2 * std::numbers::pi * nu;
  for (double t = t0; t < t1; t += 1.0 / rate) {
    const double z = z0 + a * std::sin(w * t), z_dot = a * w * std::cos(w * t);
    m.t_s.push_back(t);
    m.z_m.push_back(z);
    m.z_dot_m_s.push_back(z_dot);
    m.restoring_force_n.push_back(stiffness(z) + c * z_dot);  // Table 1
  }
  return m;
}

std::size_t add(StreamingSlices& slices, const Motion& m, double rate) {
  return slices.add(m.t_s, m.z_m, m.z_dot_m_s, m.restoring_force_n, rate);
}

TEST(StreamingSlices, KeepsTheStiffnessAndDampingSlicesOfAKnownSurface) {
  StreamingSlices::Options o;
  o.frequency_hz = 9.0;
  StreamingSlices rfs(o);
  const double rate = 512, z0 = 0.0028, a = 0.002, c = 2.02, nu = 9.0;
  const Motion h = motion(0.0, 4.0, rate, z0, a, nu, c);
  EXPECT_EQ(add(rfs, h, rate), h.t_s.size());
  EXPECT_EQ(add(rfs, h, rate), 0u);  // taken already
  ASSERT_GT(rfs.stiffness().size(), 20u);
  ASSERT_GT(rfs.damping().size(), 20u);
  // |ż| < ε_s = 0.02 × p99(|ż|) ≤ 0.02 A ω: R − K(z) = c ż is within c ε_s.
  const double band = rfs.velocity_band_m_s();
  EXPECT_LE(band, 0.02 * a * 2 * std::numbers::pi * nu * (1 + 1e-12));
  for (const WellPoint& p : rfs.stiffness()) {
    EXPECT_LE(std::abs(p.y - stiffness(p.x)), c * band * (1 + 1e-9));
    EXPECT_TRUE(p.positive);
  }
  // Damping slice: R = K(z) + c ż with |z − z̄| < ε_d; the least-squares slope of R against ż is
  // c up to K'(z̄) ε_d / (ż range) — K' = −550 + … N/m over ≤ 0.2 mm against ż up to 0.11 m/s.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(rfs.damping().size());
  for (const WellPoint& p : rfs.damping()) {
    EXPECT_LT(std::abs(p.x), a * 2 * std::numbers::pi * nu * (1 + 1e-12));
    sx += p.x, sy += p.y, sxx += p.x * p.x, sxy += p.x * p.y;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(slope, c, 0.05 * c);
  EXPECT_NEAR(rfs.damping_centre_m(), z0, 0.05 * a);  // median of a sine: its centre
}

TEST(StreamingSlices, TakesOnlyFiniteNewSamplesAndKeepsTheNewestPoints) {
  StreamingSlices::Options o;
  o.max_points = 50;
  StreamingSlices rfs(o);
  Motion h = motion(0.0, 2.0, 512, -0.0028, 0.002, 9.0, 2.0);
  for (std::size_t i = 600; i < h.t_s.size(); ++i) h.z_m[i] = std::nan("");  // not derived yet
  EXPECT_EQ(add(rfs, h, 512), 600u);
  EXPECT_NEAR(rfs.taken_until_s(), 599.0 / 512, 1e-12);
  EXPECT_LE(rfs.stiffness().size(), 50u);
  for (const WellPoint& p : rfs.stiffness()) EXPECT_FALSE(p.positive);
  h = motion(0.0, 2.0, 512, -0.0028, 0.002, 9.0, 2.0);  // now derived: the rest is taken
  EXPECT_EQ(add(rfs, h, 512), h.t_s.size() - 600);
}

// A simulated stepped-sine recording (§3.2) through the offline analysis: its z, ż and R fed to
// the streaming slices in one piece, with a window of cycles that holds the whole record, make
// the band of the offline stiffness slice (ε_s = 0.02 p99(|ż|) over the same samples) and so
// select exactly the same (z, R) points, in the same order: the comparison is exact.
// A stepped sine of `levels_n` held `hold_s` each after a 1 s lead-in.
SteppedSineSchedule stepped(std::vector<double> levels_n, double hold_s) {
  SteppedSineSchedule schedule;
  schedule.levels_n = std::move(levels_n);
  schedule.hold_s = hold_s;
  schedule.lead_in_s = 1.0;
  return schedule;
}

// The offline analysis of the virtual rig's recording of `schedule` (sensor noise seed `seed`).
CampaignAnalysis rig_campaign(const SteppedSineSchedule& schedule, std::uint64_t seed,
                              const PipelineSettings& settings) {
  daq::RigSpec spec;
  spec.seed = seed;
  return analyze_campaign({daq::measurement_channels(
                              daq::record_stepped_sine(paper_model(), schedule, spec).recording)},
                          settings);
}

TEST(StreamingSlices, SelectTheOfflineStiffnessSliceOfARecording) {
  const SteppedSineSchedule schedule = stepped({0.5, 1.5}, 4.0);
  const PipelineSettings settings;
  const CampaignAnalysis campaign = rig_campaign(schedule, 8, settings);
  ASSERT_TRUE(campaign.stiffness.has_value()) << campaign.rfs_message;
  const MotionSignals& motion = campaign.records.at(0).motion;

  // The samples the offline slice may use (away from the record's ends, finite R), in order.
  std::vector<double> t, z, z_dot, r;
  for_each_slice_sample(motion, settings.edge_trim_s, [&](Eigen::Index i) {
    t.push_back(motion.t_s[i]);
    z.push_back(motion.z_m[i]);
    z_dot.push_back(motion.z_dot_m_s[i]);
    r.push_back(motion.restoring_force_n[i]);
  });
  const double rate_hz = 1.0 / (motion.t_s[1] - motion.t_s[0]);
  StreamingSlices::Options o;
  o.velocity_band_rel = settings.stiffness_velocity_band_rel;
  o.frequency_hz = schedule.frequency_hz;
  o.cycles = static_cast<int>(std::ceil(t.size() * o.frequency_hz / rate_hz)) + 1;  // all of it
  o.max_points = t.size();
  StreamingSlices live(o);
  ASSERT_EQ(live.add(t, z, z_dot, r, rate_hz), t.size());

  const StiffnessSlice& offline = *campaign.stiffness;
  EXPECT_EQ(live.velocity_band_m_s(), offline.velocity_band_m_s);
  std::vector<double> offline_z, offline_r;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (std::abs(z_dot[i]) < offline.velocity_band_m_s) {
      offline_z.push_back(z[i]);
      offline_r.push_back(r[i]);
    }
  }
  ASSERT_EQ(live.stiffness().size(), offline_z.size());
  ASSERT_GT(offline_z.size(), 100u);
  for (std::size_t i = 0; i < offline_z.size(); ++i) {
    EXPECT_EQ(live.stiffness()[i].x, offline_z[i]) << i;
    EXPECT_EQ(live.stiffness()[i].y, offline_r[i]) << i;
  }
  // The offline fit of these very points: the cubic of eq. (2) from the live points is the
  // offline one (same samples, same order, same arithmetic).
  std::vector<double> live_z, live_r;
  for (const WellPoint& p : live.stiffness()) live_z.push_back(p.x), live_r.push_back(p.y);
  const PolynomialFit fit = fit_polynomial(
      Eigen::Map<const Eigen::VectorXd>(live_z.data(), static_cast<Eigen::Index>(live_z.size())),
      Eigen::Map<const Eigen::VectorXd>(live_r.data(), static_cast<Eigen::Index>(live_r.size())),
      3);
  for (int k = 0; k <= 3; ++k) EXPECT_EQ(fit.coefficients[k], offline.fit.coefficients[k]) << k;
}

// As the live monitor feeds them: blocks of 0.25 s, the bands from the last 30 cycles. On one
// steady level the band of the last 30 cycles is the offline band up to the scatter of a 99th
// percentile taken over 30 cycles instead of the whole level, so the two selections differ only
// in samples whose |ż| lies between the two bands. Near a turning point ż is linear in time, so
// |ż| is spread evenly below the band: a relative band difference δ leaves about δ of the
// selected samples between them. The test allows twice that, plus two for counting noise.
TEST(StreamingSlices, FedInBlocksSelectTheOfflineStiffnessSliceOfASteadyLevel) {
  const SteppedSineSchedule schedule = stepped({1.5}, 30.0);
  const PipelineSettings settings;
  const CampaignAnalysis campaign = rig_campaign(schedule, 9, settings);
  ASSERT_TRUE(campaign.stiffness.has_value()) << campaign.rfs_message;
  const MotionSignals& motion = campaign.records.at(0).motion;
  // Compared once the window of 30 cycles lies within the steady level.
  const double from_s = schedule.steady_start_s(0) + 30.0 / schedule.frequency_hz;

  std::vector<double> t, z, z_dot, r;
  for_each_slice_sample(motion, settings.edge_trim_s, [&](Eigen::Index i) {
    if (motion.t_s[i] < schedule.steady_start_s(0)) return;  // the live window: steady cycles
    t.push_back(motion.t_s[i]);
    z.push_back(motion.z_m[i]);
    z_dot.push_back(motion.z_dot_m_s[i]);
    r.push_back(motion.restoring_force_n[i]);
  });
  const double rate_hz = 1.0 / (motion.t_s[1] - motion.t_s[0]);
  StreamingSlices::Options o;
  o.velocity_band_rel = settings.stiffness_velocity_band_rel;
  o.frequency_hz = schedule.frequency_hz;
  o.max_points = t.size();
  StreamingSlices live(o);
  const auto block = static_cast<std::size_t>(0.25 * rate_hz);
  std::vector<bool> selected(t.size(), false);  // by the live slice
  const double offline_band = campaign.stiffness->velocity_band_m_s;
  double band_difference = 0.0;  // largest relative difference over the compared span
  for (std::size_t start = 0; start < t.size(); start += block) {
    const std::size_t end = std::min(t.size(), start + block);
    const std::vector<double> bt(t.begin() + start, t.begin() + end),
        bz(z.begin() + start, z.begin() + end), bv(z_dot.begin() + start, z_dot.begin() + end),
        br(r.begin() + start, r.begin() + end);
    const std::size_t kept = live.stiffness().size();
    ASSERT_EQ(live.add(bt, bz, bv, br, rate_hz), bt.size());
    // The block's new stiffness points: its samples with |ż| under the band just computed.
    std::size_t next = kept;
    for (std::size_t i = start; i < end; ++i) {
      selected[i] = std::abs(z_dot[i]) < live.velocity_band_m_s();
      if (!selected[i]) continue;
      ASSERT_LT(next, live.stiffness().size());
      EXPECT_EQ(live.stiffness()[next].x, z[i]);
      EXPECT_EQ(live.stiffness()[next].y, r[i]);
      ++next;
    }
    ASSERT_EQ(next, live.stiffness().size());
    if (t[start] >= from_s) {
      band_difference =
          std::max(band_difference, std::abs(live.velocity_band_m_s() / offline_band - 1.0));
    }
  }
  std::size_t compared = 0, offline_points = 0, disagree = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < from_s) continue;
    ++compared;
    const bool offline = std::abs(z_dot[i]) < offline_band;
    offline_points += offline;
    disagree += offline != selected[i];
  }
  ASSERT_GT(offline_points, 100u);
  EXPECT_LT(band_difference, 0.05);  // a p99 of 30 cycles of one steady level
  EXPECT_LE(static_cast<double>(disagree),
            2.0 * band_difference * static_cast<double>(offline_points) + 2.0)
      << disagree << " of " << offline_points << " offline points differ, bands within "
      << band_difference << " (" << compared << " samples compared)";
}

}  // namespace
}  // namespace oscilab::analysis
