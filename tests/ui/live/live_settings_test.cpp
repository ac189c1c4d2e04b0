// The live settings round trip and their validation, and the rig's stepped schedule.
#include "ui/live/live_settings.h"

#include <string>

#include <gtest/gtest.h>

#include "analysis/common/input_error.h"

namespace oscilab::ui {
namespace {

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
  // Each names the field's path and the bad value.
  EXPECT_EQ(message({{"replay_loop", "yes"}}),
            "live.replay_loop: expected true or false, got \"yes\"");
  EXPECT_EQ(message({{"replay_path", 3}}), "live.replay_path: expected a string, got 3");
  EXPECT_EQ(message({{"jack", 1}}), "live.jack: expected an object, got 1");
  EXPECT_EQ(message({{"rig", {{"well", "left"}}}}),
            "live.rig.well: expected \"positive\" or \"negative\", got \"left\"");
  EXPECT_EQ(message({{"speed", "fast"}}), "live.speed: expected a number, got \"fast\"");
  EXPECT_EQ(message({{"port", 70000}}), "live.port: 70000 (a TCP port, 0 to 65535)");
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

}  // namespace
}  // namespace oscilab::ui
