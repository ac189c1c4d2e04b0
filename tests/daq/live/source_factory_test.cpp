#include "daq/live/source_factory.h"

#include <gtest/gtest.h>

#include "daq/network/net_source.h"
#include "daq/sources/replay_source.h"
#include "daq/sources/rig_source.h"
#include "tests/input_error_of.h"

namespace oscilab::daq {
namespace {

using oscilab::testing::input_error_of;

TEST(SourceFactory, NamesTheKindOfEveryDescription) {
  EXPECT_EQ(source_kind("rig"), SourceKind::Rig);
  EXPECT_EQ(source_kind("net:127.0.0.1:5025"), SourceKind::Network);
  EXPECT_EQ(source_kind("jack:system:capture_1,system:capture_2"), SourceKind::Jack);
  EXPECT_EQ(source_kind("file:run.wav"), SourceKind::Replay);
  EXPECT_EQ(source_kind("run.wav"), SourceKind::Replay);
}

TEST(SourceFactory, MakesTheRigAReplayAndAReceiver) {
  SourceOptions o;
  o.rig.frequency_hz = 7.0;
  o.rig.schedule = rig_schedule({0.5}, 2.0, 0.5, 7.0);
  const auto rig = make_source("rig", o);
  ASSERT_NE(dynamic_cast<RigSource*>(rig.get()), nullptr);
  EXPECT_EQ(rig->layout()->excitation->frequency_hz, 7.0);
  const std::string sample = std::string(OSCILAB_SOURCE_DIR) + "/samples/stepped_positive.flac";
  for (const std::string& spec : {"file:" + sample, sample}) {
    const auto replay = make_source(spec, o);
    ASSERT_NE(dynamic_cast<ReplaySource*>(replay.get()), nullptr);
  }
  const auto net = make_source("net:127.0.0.1:0", o);  // port 0: any free port
  ASSERT_NE(dynamic_cast<NetSource*>(net.get()), nullptr);
  EXPECT_GT(dynamic_cast<NetSource*>(net.get())->port(), 0);
}

TEST(SourceFactory, RefusesBadDescriptionsNamingTheOption) {
  SourceOptions o;
  EXPECT_EQ(input_error_of([&] { make_source("file:", o); }),
            "--source file: needs a recording path");
  EXPECT_EQ(input_error_of([&] { make_source("net:nowhere", o); }),
            "--source: \"nowhere\" is not HOST:PORT");
  o.what = "source";
  EXPECT_EQ(input_error_of([&] { make_source("net:127.0.0.1:70000", o); }),
            "source: port \"70000\" is not within 1..65535");
  EXPECT_EQ(input_error_of([&] { make_source("jack:a,b", o); }),
            "source jack:a,b: a JACK source needs its calibration (a sidecar with one channel per "
            "port)");
  // The rig starts in a well, not across them.
  o.rig.well = analysis::Well::CrossWell;
  EXPECT_EQ(input_error_of([&] { make_source("rig", o); }),
            "source rig: the rig starts in the positive or the negative well, not \"cross-well\"");
  o.rig.well = analysis::Well::Negative;
  EXPECT_NE(dynamic_cast<RigSource*>(make_source("rig", o).get()), nullptr);
  // A kind it does not know is named as such, not taken for a missing file.
  o.what = "--source";
  EXPECT_EQ(input_error_of([&] { make_source("usb:3", o); }),
            "--source usb:3: unknown source kind \"usb:\" (rig, net:HOST:PORT, "
            "jack:PORT_BASE,PORT_MASS, file:REC or a recording's path)");
  const std::string missing = input_error_of([&] { make_source("run.wav", o); });
  EXPECT_NE(missing.find("run.wav: file not found"), std::string::npos) << missing;
}

}  // namespace
}  // namespace oscilab::daq
