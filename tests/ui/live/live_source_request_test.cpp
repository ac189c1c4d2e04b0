// The source the live settings describe, as the one source factory reads it: the spec names the
// kind (daq::source_kind), the options carry the rig's and the replay's fields, and a source
// that lacks a field it needs is refused with a message naming it.
#include "ui/live/live_source_request.h"

#include <string>

#include <gtest/gtest.h>

#include "tests/input_error_of.h"

namespace oscilab::ui {
namespace {

using oscilab::testing::input_error_of;

TEST(LiveSourceRequest, NamesEachKindAsTheSourceFactoryReadsIt) {
  LiveSettings s;
  s.rig_positive_well = false;
  s.rig_frequency_hz = 8.5;
  s.speed = 10.0;
  const std::vector<daq::ExcitationStep> schedule = stepped_schedule(0.2, 0.4, 0.1, 6, 1, 8.5);
  const LiveSourceRequest rig = live_source_request(s, schedule, 30.0);
  EXPECT_EQ(rig.spec, "rig");
  EXPECT_EQ(daq::source_kind(rig.spec), daq::SourceKind::Rig);
  EXPECT_EQ(rig.options.rig.well, analysis::Well::Negative);
  EXPECT_EQ(rig.options.rig.frequency_hz, 8.5);
  EXPECT_EQ(rig.options.rig.speed, 10.0);
  EXPECT_EQ(rig.options.replay.speed, 10.0);
  EXPECT_EQ(rig.options.rig.schedule.size(), schedule.size());
  EXPECT_EQ(rig.options.rig.duration_s, 30.0);

  s.source = LiveSourceKind::Replay;
  s.replay_path = "/data/run 1.flac";
  s.replay_loop = true;
  const LiveSourceRequest replay = live_source_request(s, {}, std::nullopt);
  EXPECT_EQ(replay.spec, "file:/data/run 1.flac");
  EXPECT_EQ(daq::source_kind(replay.spec), daq::SourceKind::Replay);
  EXPECT_TRUE(replay.options.replay.loop);

  s.source = LiveSourceKind::Network;
  s.port = 0;  // any free port
  const LiveSourceRequest network = live_source_request(s, {}, std::nullopt);
  EXPECT_EQ(network.spec, "net:127.0.0.1:0");
  EXPECT_EQ(daq::source_kind(network.spec), daq::SourceKind::Network);
}

TEST(LiveSourceRequest, ThrowsInputErrorWhenTheSourceLacksAField) {
  LiveSettings s;
  s.source = LiveSourceKind::Replay;
  EXPECT_NE(input_error_of([&] { live_source_request(s, {}, std::nullopt); }).find("replay"),
            std::string::npos);
  s.source = LiveSourceKind::Jack;
  EXPECT_NE(input_error_of([&] { live_source_request(s, {}, std::nullopt); }).find("JACK"),
            std::string::npos);
  s.jack_calibration = "/nonexistent/calibration.json";
  EXPECT_NE(input_error_of([&] {
              live_source_request(s, {}, std::nullopt);
            }).find("/nonexistent/calibration.json"),
            std::string::npos);
}

}  // namespace
}  // namespace oscilab::ui
