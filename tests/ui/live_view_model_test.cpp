// The live monitor's Qt-free logic: settings, schedule, time window and scroll-back,
// fault counting and colouring, status and event texts, EDC points, display units and axes,
// each against an independent expectation.
#include "ui/live_view_model.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::ui {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(LiveSettings, RoundTripsThroughJsonAndKeepsDefaultsForMissingFields) {
  LiveSettings s;
  s.source = LiveSourceKind::Replay;
  s.replay_path = "/data/run 1.flac";
  s.replay_loop = true;
  s.port = 0;
  s.rig_f0_n = 1.3;
  s.rig_frequency_hz = 8.5;
  s.rig_step_n = 0.05;
  s.rig_positive_well = false;
  s.speed = 0.0;
  s.window_s = 600.0;
  s.alarms.max_abs_z_m = 0.012;
  s.alarms.max_abs_force_n = 5.0;
  const LiveSettings back = LiveSettings::from_json(nlohmann::json::parse(s.to_json().dump()));
  EXPECT_EQ(back.to_json(), s.to_json());
  EXPECT_EQ(back.source, LiveSourceKind::Replay);
  EXPECT_FALSE(back.alarms.max_abs_base_m.has_value());
  EXPECT_EQ(*back.alarms.max_abs_z_m, 0.012);

  // An older session without "live" fields, or with only some: the defaults.
  EXPECT_EQ(LiveSettings::from_json(nlohmann::json::object()).to_json(), LiveSettings{}.to_json());
  EXPECT_EQ(LiveSettings::from_json(nullptr).to_json(), LiveSettings{}.to_json());
  const LiveSettings partial = LiveSettings::from_json({{"window_s", 30}});
  EXPECT_EQ(partial.window_s, 30.0);
  EXPECT_EQ(partial.rig_frequency_hz, 9.0);
}

TEST(LiveSettings, ThrowsInputErrorNamingTheField) {
  const auto message = [](const nlohmann::json& json) {
    try {
      LiveSettings::from_json(json);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"window_s", -3}}).find("live.window_s"), std::string::npos);
  EXPECT_NE(message({{"source", "tape"}}).find("live.source"), std::string::npos);
  EXPECT_NE(message({{"rig", {{"frequency_hz", "9"}}}}).find("live.rig.frequency_hz"),
            std::string::npos);
  EXPECT_NE(message({{"port", 70000}}).find("live.port"), std::string::npos);
  EXPECT_NE(message({{"alarms", {{"max_abs_z_m", 0}}}}).find("live.alarms.max_abs_z_m"),
            std::string::npos);
  EXPECT_NE(message(nlohmann::json::array()).find("live"), std::string::npos);
}

TEST(SteppedSchedule, RunsThePapersLevelsThenRests) {
  // §3.2: 0.2 → 2.7 N in 0.1 N steps: 26 levels, each held 10 s after 2.5 s at rest.
  const auto steps = stepped_schedule(0.2, 2.7, 0.1, 10.0, 2.5, 9.0);
  ASSERT_EQ(steps.size(), 27u);
  for (std::size_t i = 0; i < 26; ++i) {
    EXPECT_NEAR(steps[i].f0_n, 0.2 + 0.1 * static_cast<double>(i), 1e-12);
    EXPECT_DOUBLE_EQ(steps[i].t_s, 2.5 + 10.0 * static_cast<double>(i));
    EXPECT_EQ(steps[i].frequency_hz, 9.0);
  }
  EXPECT_EQ(steps.back().f0_n, 0.0);
  EXPECT_DOUBLE_EQ(steps.back().t_s, 262.5);  // the samples' length (README)
  EXPECT_THROW(stepped_schedule(0.0, 1.0, 0.1, 10.0, 0.0, 9.0), InputError);
  EXPECT_THROW(stepped_schedule(1.0, 0.5, 0.1, 10.0, 0.0, 9.0), InputError);
  EXPECT_THROW(stepped_schedule(0.2, 1.0, 0.1, 0.0, 0.0, 9.0), InputError);
}

TEST(LiveTimeline, FollowsTheStreamAndPausedStaysWhileTheAcquisitionGoesOn) {
  LiveTimeline timeline(10.0, 600.0);
  timeline.advance(3.0);  // less than a window: the first 10 s
  EXPECT_EQ(timeline.view().start_s, 0.0);
  EXPECT_EQ(timeline.view().end_s, 10.0);
  timeline.advance(42.0);
  EXPECT_EQ(timeline.view().start_s, 32.0);
  EXPECT_EQ(timeline.view().end_s, 42.0);

  timeline.pause();
  timeline.advance(100.0);
  EXPECT_FALSE(timeline.following());
  EXPECT_EQ(timeline.view().end_s, 42.0);  // the view stays, the stream went on
  timeline.scroll_to(20.0);
  EXPECT_EQ(timeline.view().end_s, 20.0);
  timeline.scroll_to(-5.0);  // before the oldest window: clamped to it
  EXPECT_EQ(timeline.view().start_s, 0.0);
  timeline.scroll_to(1e9);  // after now: clamped to now
  EXPECT_EQ(timeline.view().end_s, 100.0);

  // 10 minutes kept: once the history moved past the paused window, the oldest kept is shown.
  timeline.scroll_to(30.0);
  timeline.advance(700.0);
  EXPECT_EQ(timeline.scroll_range().start_s, 110.0);
  EXPECT_EQ(timeline.scroll_range().end_s, 700.0);
  EXPECT_EQ(timeline.view().start_s, 100.0);
  timeline.resume();
  EXPECT_EQ(timeline.view().end_s, 700.0);
  timeline.set_window_s(5000.0);  // no wider than the history
  EXPECT_EQ(timeline.window_s(), 600.0);
}

daq::StreamEvent event(const std::string& kind, nlohmann::json data = nlohmann::json::object()) {
  return {1.0, kind, "", std::move(data)};
}

TEST(FaultCounts, CountsLoggedFaultsAndTakesTheLargerOfTheAcquisitionsCounts) {
  FaultCounts counts;
  counts.add(event("gap", {{"samples", 32}}));
  counts.add(event("gap", {{"samples", 64}}));
  counts.add(event("duplicate", {{"sequence", 90}}));
  counts.add(event("reordered"));
  counts.add(event("non-finite", {{"samples", 3}}));
  counts.add(event("saturated", {{"samples", 1}}));
  counts.add(event("overflow", {{"blocks", 100}}));
  counts.add(event("alarm"));
  counts.add(event("mark"));
  counts.add(event("level", {{"f0_n", 1.0}}));
  EXPECT_EQ(counts.gaps, 2u);
  EXPECT_EQ(counts.gap_samples, 96u);
  EXPECT_EQ(counts.duplicates, 1u);
  EXPECT_EQ(counts.reordered, 1u);
  EXPECT_EQ(counts.non_finite_samples, 3u);
  EXPECT_EQ(counts.saturated_samples, 1u);
  EXPECT_EQ(counts.overflowed_blocks, 100u);
  EXPECT_EQ(counts.alarms, 1u);

  daq::AcquisitionStatus status;  // after stop: the StreamMonitor's exact counts
  status.gaps = 2;
  status.gap_samples = 96;
  status.overflowed_blocks = 137;  // the source's counter: events come once per 100
  status.non_finite_samples = 3;
  const FaultCounts merged = counts.merged(status);
  EXPECT_EQ(merged.gap_samples, 96u);
  EXPECT_EQ(merged.overflowed_blocks, 137u);
  EXPECT_EQ(merged.duplicates, 1u);
}

TEST(FaultTracker, ACounterThatRoseIsRedThenAmber) {
  FaultTracker tracker(5.0);
  FaultCounts counts;
  tracker.update(counts, 0.0);
  EXPECT_EQ(tracker.severity("gaps", 0.0), Severity::Normal);
  counts.gaps = 1;
  counts.gap_samples = 32;
  tracker.update(counts, 10.0);
  EXPECT_EQ(tracker.severity("gaps", 10.0), Severity::Fault);
  EXPECT_EQ(tracker.severity("gaps", 14.9), Severity::Fault);
  tracker.update(counts, 15.1);  // no new gap
  EXPECT_EQ(tracker.severity("gaps", 15.1), Severity::Warning);
  EXPECT_EQ(tracker.severity("duplicates", 15.1), Severity::Normal);
}

TEST(ThroughputMeter, MeasuresSamplesPerWallSecond) {
  ThroughputMeter meter(1.0);
  EXPECT_EQ(meter.samples_per_s(), 0.0);
  for (int i = 0; i <= 30; ++i) meter.add(0.1 * i, static_cast<std::uint64_t>(5120 * i));
  EXPECT_NEAR(meter.samples_per_s(), 51200.0, 1e-6);  // 100× of 512 Hz
  meter.add(3.1, 0);                                  // a new stream: starts over
  EXPECT_EQ(meter.samples_per_s(), 0.0);
}

TEST(StatusFields, ShowEveryFigureOfTheIssueWithItsSeverity) {
  daq::AcquisitionStatus s;
  s.source = "virtual rig";
  s.running = true;
  s.sample_rate_hz = 512;
  s.stream_time_s = 12.25;
  s.samples = 6272;
  s.queue_fill = 200;
  s.queue_capacity = 256;
  s.recording = true;
  s.recorded_samples = 1024;
  s.cycles = 90;
  s.excluded_cycles = 2;
  s.edc_latency_s = 0.031;
  FaultCounts faults;
  faults.gaps = 1;
  faults.gap_samples = 32;
  FaultTracker tracker;
  tracker.update(faults, 1.0);
  const auto fields = status_fields(s, faults, tracker, 1.0, 5120.0);
  std::map<std::string, StatusField> by_key;
  for (const auto& f : fields) by_key[f.key] = f;
  for (const char* key :
       {"source", "rate", "time", "samples", "gaps", "duplicates", "reordered", "nan", "saturated",
        "overflow", "queue", "recording", "cycles", "levels", "latency", "alarms", "errors"}) {
    EXPECT_EQ(by_key.count(key), 1u) << key;
  }
  EXPECT_EQ(by_key["rate"].value, "512 Hz \u00d710");
  EXPECT_EQ(by_key["time"].value, "12.2 s");  // %.1f rounds half to even on 12.25
  EXPECT_EQ(by_key["samples"].value, "6272");
  EXPECT_EQ(by_key["gaps"].value, "32 (1)");
  EXPECT_EQ(by_key["gaps"].severity, Severity::Fault);
  EXPECT_EQ(by_key["duplicates"].severity, Severity::Normal);
  EXPECT_EQ(by_key["queue"].value, "200/256");
  EXPECT_EQ(by_key["queue"].severity, Severity::Warning);  // over 3/4 full
  EXPECT_EQ(by_key["recording"].value, "\u25cf 2.0 s");    // 1024 samples at 512 Hz
  EXPECT_EQ(by_key["cycles"].value, "90 (2 excl.)");
  EXPECT_EQ(by_key["latency"].value, "31 ms");
}

TEST(EventRow, FormatsTimeAndMarksFaults) {
  const EventRow gap = event_row({12.5, "gap", "32 sample(s) never arrived"});
  EXPECT_EQ(gap.time, "12.500 s");
  EXPECT_EQ(gap.severity, Severity::Fault);
  const EventRow connected =
      event_row({std::numeric_limits<double>::quiet_NaN(), "connected", "sender x"});
  EXPECT_EQ(connected.time, "\u2014");
  EXPECT_EQ(connected.severity, Severity::Normal);
  EXPECT_EQ(event_row({1.0, "duplicate", "block 9"}).severity, Severity::Warning);
  EXPECT_EQ(event_row({1.0, "level", "", {{"f0_n", 1.0}}}).text, "{\"f0_n\":1.0}");
}

analysis::LevelResult level(const char* well, double f0, double edc, double std, int cycles) {
  analysis::LevelResult r;
  r.well = well;
  r.f0_n = f0;
  r.edc_mean_j = edc;
  r.edc_std_j = std;
  r.cycles = cycles;
  return r;
}

TEST(EdcPlotData, SplitsLevelsByWellWithThreeSigmaBars) {
  std::vector<analysis::LevelResult> levels = {
      level("positive", 0.2, 1e-5, 1e-7, 80), level("negative", 0.2, 2e-5, 2e-7, 80),
      level("positive", 0.3, 3e-5, 1e-7, 80), level("cross-well", 2.9, 1e-2, 1e-3, 80)};
  levels[3].cross_well = true;
  const EdcPlotData data = edc_plot_data(levels, level("positive", 0.4, 4e-5, 1e-7, 12));
  ASSERT_EQ(data.positive.size(), 2u);
  ASSERT_EQ(data.negative.size(), 1u);
  ASSERT_EQ(data.other.size(), 1u);
  EXPECT_EQ(data.positive[1].f0_n, 0.3);
  EXPECT_EQ(data.positive[1].edc_j, 3e-5);
  EXPECT_DOUBLE_EQ(data.negative[0].error_j, 6e-7);  // Fig. 10: ±3σ
  EXPECT_EQ(data.other[0].flags, "cross-well");
  ASSERT_TRUE(data.current.has_value());
  EXPECT_EQ(data.current->f0_n, 0.4);
  EXPECT_EQ(data.current_well, "positive");
  EXPECT_EQ(data.max_f0_n, 2.9);
  // A level with no steady cycle yet is not drawn.
  EXPECT_FALSE(edc_plot_data({}, level("positive", 0.5, 0, 0, 0)).current.has_value());
}

TEST(PredictionLevels, CoverThePapersRangeOrThatMeasured) {
  const auto levels = prediction_levels(1.0);
  EXPECT_DOUBLE_EQ(levels.front(), 0.1);
  EXPECT_NEAR(levels.back(), 2.7, 1e-9);
  EXPECT_EQ(levels.size(), 53u);  // 0.1 … 2.7 in 0.05 N
  for (std::size_t i = 1; i < levels.size(); ++i) EXPECT_GT(levels[i], levels[i - 1]);
  EXPECT_GE(prediction_levels(3.0).back(), 3.1 - 1e-9);
}

TEST(LevelWarning, NamesTheFlagsOfTheLevelBeingFilled) {
  EXPECT_EQ(level_warning(std::nullopt), "");
  analysis::LevelResult r = level("positive", 2.8, 1e-2, 1e-4, 40);
  EXPECT_EQ(level_warning(r), "");
  r.period1 = false;
  r.cross_well = true;
  EXPECT_NE(level_warning(r).find("not period-1"), std::string::npos);
  EXPECT_NE(level_warning(r).find("crosses wells"), std::string::npos);
}

TEST(StickyDisplayUnit, KeepsTheUnitNearAPrefixBoundary) {
  const DisplayUnit mm = sticky_display_unit(std::nullopt, "m", 4e-3);
  EXPECT_EQ(mm.symbol, "mm");
  EXPECT_EQ(sticky_display_unit(mm, "m", 0.6e-3).symbol, "mm");  // 0.6 mm: still mm
  EXPECT_EQ(sticky_display_unit(mm, "m", 0.3e-3).symbol, "\u00b5m");
  EXPECT_EQ(sticky_display_unit(mm, "m", 0.0).symbol, "mm");  // no data: unchanged
  EXPECT_EQ(sticky_display_unit(mm, "m", 2.5).symbol, "m");
}

TEST(FollowRange, GrowsAtOnceAndShrinksOnlyWhenTheDataFillLittle) {
  const AxisRange first = follow_range(std::nullopt, -1.0, 1.0);
  EXPECT_DOUBLE_EQ(first.lo, -1.2);
  EXPECT_DOUBLE_EQ(first.hi, 1.2);
  const AxisRange same = follow_range(first, -0.9, 0.8);  // inside, fills 71 %: unchanged
  EXPECT_EQ(same.lo, first.lo);
  EXPECT_EQ(same.hi, first.hi);
  const AxisRange grown = follow_range(first, -1.0, 2.0);
  EXPECT_GE(grown.hi, 2.0);
  const AxisRange shrunk = follow_range(grown, -0.1, 0.1);
  EXPECT_NEAR(shrunk.hi, 0.12, 1e-12);
  EXPECT_EQ(follow_range(first, std::nan(""), 1.0).lo, first.lo);
}

}  // namespace
}  // namespace oscilab::ui
