#include "analysis/simulation/time_simulator.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/model/polynomial_stiffness.h"
#include "analysis/model/reference_models.h"
#include "analysis/model/viscous_damping.h"
#include "analysis/simulation/random_motion.h"
#include "analysis/simulation/stepped_sine_run.h"
#include "tests/input_error_of.h"

namespace oscilab::analysis {
namespace {

// A run too long or too fast for memory is one InputError before anything is allocated, not
// std::bad_alloc after gigabytes (simulate --hold 1e9, --rate 1e9, --duration 1e9).
TEST(TimeSimulator, RefusesARunOfMoreSamplesThanTheLimitBeforeAllocating) {
  const Model model = linear_oscillator_model(0.5, 2000.0, 4.0);
  SteppedSineSchedule schedule;
  schedule.frequency_hz = 7.0;
  schedule.levels_n = {1.5};
  schedule.hold_s = 1e9;
  schedule.ramp_s = 0.5;
  const SteppedSineMotion motion(schedule, 0.5);
  const TimeSimulator simulator(model, {});
  TimeSimulator::Run run;
  run.duration_s = schedule.duration_s();
  run.sample_rate_hz = 512.0;
  EXPECT_EQ(testing::input_error_of([&] { simulator.simulate(motion, run); }),
            "time simulation: 1e+09 s at 512 Hz is 5.12e+11 samples, more than the 5e+07 one run "
            "holds (a day at 512 Hz is 4.4e+07)");
  run.duration_s = 10.0;
  run.sample_rate_hz = 1e9;
  EXPECT_NE(testing::input_error_of([&] { simulator.simulate(motion, run); }).find("1e+10 samples"),
            std::string::npos);
  // A day at 512 Hz, the longest test a lab runs, stays within the limit.
  EXPECT_LT(86400.0 * 512.0, TimeSimulator::kMaxSamples);

  RandomMotionSpec random;
  random.duration_s = 1e9;
  EXPECT_EQ(testing::input_error_of([&] { RandomMotion(random, 0.5); }),
            "random excitation: duration 1e+09 s needs 4.1e+12 grid points at 4096 Hz, more than "
            "the 3.36e+07 (8192 s) it may hold");
}

TEST(TimeSimulator, LinearOscillatorReachesClosedFormSteadyState) {
  const double m = 0.5, k = 2000.0, c = 4.0;  // ω_n = 63 rad/s, decay c/2m = 4 s⁻¹
  const Model model = linear_oscillator_model(m, k, c);
  SteppedSineSchedule schedule;
  schedule.frequency_hz = 7.0;
  schedule.levels_n = {1.5};
  schedule.hold_s = 12.0;
  schedule.ramp_s = 0.5;
  schedule.lead_in_s = 0.0;
  const SteppedSineMotion motion(schedule, m);
  const TimeSimulator simulator(model, {});
  TimeSimulator::Run run;
  run.duration_s = schedule.duration_s();
  run.sample_rate_hz = 512.0;
  const auto result = simulator.simulate(motion, run);
  ASSERT_EQ(result.status, TimeSimulator::Status::Ok);

  // Steady state of m z̈ + c ż + k z = f0 sin ωt: z = f0/|k − mω² + icω| sin(ωt − φ),
  // φ = atan2(cω, k − mω²).
  const double w = 2 * std::numbers::pi * schedule.frequency_hz;
  const double amplitude = 1.5 / std::hypot(k - m * w * w, c * w);
  const double phase = std::atan2(c * w, k - m * w * w);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < result.t_s.size(); ++i) {
    const double t = result.t_s[i];
    if (t < 8.0) continue;  // the transient has decayed by e^{-4·7.5} = 1e-13 after the ramp
    worst = std::max(worst, std::abs(result.z_m[i] - amplitude * std::sin(w * t - phase)));
  }
  // Local error per step ~1e-9 relative accumulates over ~1e4 steps at worst linearly: 1e-7.
  EXPECT_LT(worst / amplitude, 1e-7);

  // The dissipated energy per cycle of a linear viscous damper is π c ω Z² (closed form).
  const SteppedSineRun levels = simulate_stepped_sine(simulator, motion, 0.0, 512.0);
  ASSERT_EQ(levels.levels.size(), 1u);
  const double edc_closed = std::numbers::pi * c * w * amplitude * amplitude;
  EXPECT_NEAR(levels.levels[0].edc_j / edc_closed, 1.0, 1e-8);
}

SteppedSineSchedule short_paper_test() {
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.2, 1.3, 2.7};
  schedule.hold_s = 6.0;
  schedule.lead_in_s = 0.5;
  return schedule;
}

TEST(TimeSimulator, EnergyBalanceClosesOnThePaperModel) {
  const Model model = paper_model();
  const SteppedSineMotion motion(short_paper_test(), model.mass_kg());
  const TimeSimulator simulator(model, {});
  for (bool positive : {true, false}) {
    const double z0 = model.well(positive).z_m;
    TimeSimulator::Run run;
    run.z0_m = z0;
    run.duration_s = motion.duration_s();
    run.probe_times_s = {0.0, run.duration_s};
    const auto r = simulator.simulate(motion, run);
    ASSERT_EQ(r.status, TimeSimulator::Status::Ok);
    // W_in − W_diss − ΔE_mech, with W from the integrator's own augmented states.
    const double work_in = r.probe_work_in_j[1];
    const double imbalance =
        work_in - r.probe_dissipated_j[1] - (r.probe_mechanical_j[1] - r.probe_mechanical_j[0]);
    // The input work over the test is a few joules; the brief's bound is 1e-6 of it.
    EXPECT_GT(std::abs(work_in), 1e-3);
    EXPECT_LT(std::abs(imbalance) / std::abs(work_in), 1e-6) << "well " << positive;
  }
}

TEST(TimeSimulator, HalvingTheToleranceChangesLevelEdcByLessThan1e4) {
  const Model model = paper_model();
  const SteppedSineMotion motion(short_paper_test(), model.mass_kg());
  TimeSimulator::Options tight;
  tight.relative_tolerance *= 0.5;
  tight.absolute_tolerance *= 0.5;
  const TimeSimulator simulator(model, {}), tighter(model, tight);
  for (bool positive : {true, false}) {
    const double z0 = model.well(positive).z_m;
    const auto a = simulate_stepped_sine(simulator, motion, z0, 512.0);
    const auto b = simulate_stepped_sine(tighter, motion, z0, 512.0);
    for (std::size_t i = 0; i < a.levels.size(); ++i) {
      ASSERT_GT(a.levels[i].cycles, 20);
      EXPECT_GT(a.levels[i].edc_j, 0.0);
      EXPECT_LT(std::abs(a.levels[i].edc_j / b.levels[i].edc_j - 1.0), 1e-4)
          << "level " << a.levels[i].f0_n << " N, well " << positive;
    }
  }
}

TEST(TimeSimulator, SteadyEdcEqualsForceDisplacementLoopArea) {
  // ∮ f dz over a steady cycle equals ∮ D dz (eq. (11) with ∮ m z̈ dz = ∮ K dz = 0): check the
  // simulator's energy integral against the trapezoidal loop area of its own sampled output at
  // a high output rate (second-order quadrature, 8192 samples per second).
  const Model model = paper_model();
  SteppedSineSchedule schedule;
  schedule.levels_n = {1.3};
  schedule.hold_s = 8.0;
  schedule.lead_in_s = 0.0;
  const SteppedSineMotion motion(schedule, model.mass_kg());
  const TimeSimulator simulator(model, {});
  const double rate = 9.0 * 1024;  // an integer number of samples per forcing cycle
  const auto run = simulate_stepped_sine(simulator, motion, model.well(true).z_m, rate);
  const auto& s = run.samples;
  const auto& level = run.levels[0];
  double area = 0.0;
  for (Eigen::Index i = 1; i < s.t_s.size(); ++i) {
    if (s.t_s[i - 1] < level.start_s - 1e-9 || s.t_s[i] > level.end_s + 1e-9) continue;
    area += 0.5 * (s.f_n[i] + s.f_n[i - 1]) * (s.z_m[i] - s.z_m[i - 1]);
  }
  area /= level.cycles;
  // Trapezoid error ∝ Δt²: with 1024 samples per cycle of a loop with sharp friction corners,
  // ~1e-4 relative.
  EXPECT_NEAR(area / level.edc_j, 1.0, 1e-3);
}

TEST(TimeSimulator, ReportsCancellation) {
  const Model model = paper_model();
  const SteppedSineMotion motion(short_paper_test(), model.mass_kg());
  const TimeSimulator simulator(model, {});
  CancelToken cancel;
  int calls = 0;
  TimeSimulator::Run run;
  run.duration_s = motion.duration_s();
  run.z0_m = model.well(true).z_m;
  const auto r = simulator.simulate(
      motion, run,
      [&](double) {
        if (++calls == 3) cancel.cancel();
      },
      cancel);
  EXPECT_EQ(r.status, TimeSimulator::Status::Cancelled);
  EXPECT_EQ(r.t_s.size(), 1 + 3 * 512);  // the initial sample and three one-second chunks
}

}  // namespace
}  // namespace oscilab::analysis

namespace oscilab::analysis {
namespace {

TEST(TimeSimulator, OutputRateDoesNotChangeTheDynamics) {
  // Regression: states were interpolated from the dense output between steps, with an error of
  // ~(ωh)⁵ ≈ 1e-5 of the state, so EDCs depended on the output rate (1e-4, and 8 % at one level
  // where that perturbation sent the response to another attractor). Steps now land on outputs.
  const Model model = paper_model();
  SteppedSineSchedule schedule;
  schedule.levels_n = {0.5, 1.7};
  schedule.hold_s = 8.0;
  const SteppedSineMotion motion(schedule, model.mass_kg());
  const TimeSimulator simulator(model, {});
  const double z0 = model.well(true).z_m;
  const auto slow = simulate_stepped_sine(simulator, motion, z0, 64.0);
  const auto fast = simulate_stepped_sine(simulator, motion, z0, 512.0);
  for (std::size_t i = 0; i < slow.levels.size(); ++i) {
    // Different step sequences, each accurate to the tolerance (1e-9 per step): 1e-6 relative.
    EXPECT_NEAR(slow.levels[i].edc_j / fast.levels[i].edc_j, 1.0, 1e-6) << "level " << i;
  }
}

}  // namespace
}  // namespace oscilab::analysis
