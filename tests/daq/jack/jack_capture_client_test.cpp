// The JACK capture client against a real jackd (dummy backend): a ring nobody drains fills, and
// the real-time callback drops the frames it has no room for and counts them; a client whose
// server was killed is closed only once libjack's thread that reported it has settled, and the
// process opens clients again when the server is back.
#include "daq/jack/jack_capture_client.h"

#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include <unistd.h>

#include <gtest/gtest.h>

#include "tests/daq/jack/jack_test_server.h"

namespace oscilab::daq {
namespace {

using testing::JackTestPlayer;
using testing::JackTestServer;

TEST(JackCaptureClient, ARingNobodyDrainsFillsAndTheFramesWithoutRoomAreCounted) {
  JackTestServer server(48000, 256);
  JackTestPlayer player(server.name(), 1);
  JackCaptureClient::Options options;
  options.server = server.name();
  options.client_name = "capture-test";
  options.capture_ports = {player.port(0)};
  options.channel_names = {"base"};
  options.ring_s = 0.05;  // 2400 frames: full after some 10 periods
  JackCaptureClient client(options);
  ASSERT_EQ(client.open(), "");
  ASSERT_EQ(client.activate(), "");
  // A guard of a minute against a hang; the ring is full within 50 ms of the server's clock.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (client.dropped_frames() == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const std::uint64_t dropped = client.dropped_frames();
  ASSERT_GT(dropped, 0u) << "the callback never found the undrained ring full";
  client.deactivate();
  // The ring holds what came before it filled.
  std::uint64_t held = 0;
  while (const FrameSlot* slot = client.ring().front()) {
    held += slot->frames;
    client.ring().pop();
  }
  EXPECT_GT(held, 0u);
  client.close();
}

TEST(JackCaptureClient, AClientWhoseServerDiedClosesOnlyAfterTheShutdownSettled) {
  JackTestServer server(48000, 256);
  auto player = std::make_unique<JackTestPlayer>(server.name(), 1);
  JackCaptureClient::Options options;
  options.server = server.name();
  options.client_name = "capture-test";
  options.capture_ports = {player->port(0)};
  options.channel_names = {"base"};
  options.ring_s = 1.0;
  JackCaptureClient client(options);
  ASSERT_EQ(client.open(), "");
  ASSERT_EQ(client.activate(), "");
  player.reset();
  server.stop(SIGKILL);  // no goodbye: libjack's threads find the server gone
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (!client.shut_down() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(client.shut_down()) << "the shutdown callback never came";
  const auto reported = client.shut_down_at();
  EXPECT_LE(reported, std::chrono::steady_clock::now());
  client.close();
  EXPECT_GE(std::chrono::steady_clock::now(), reported + kJackShutdownSettle);
  // The process can open a client again once the server is back (it hung here when a lock of a
  // killed libjack thread stayed held).
  server.start();
  JackTestPlayer back(server.name(), 1);
  options.capture_ports = {back.port(0)};
  JackCaptureClient again(options);
  EXPECT_EQ(again.open(), "");
  again.close();
}

// libjack's metadata database with an empty region file (a JACK program killed while opening it)
// would fault inside jack_client_open; it is seen first and named. Checked on a folder of its own
// (the machine's real one is shared by every JACK test running beside this one).
TEST(JackMetadata, AnEmptyRegionFileIsSeenAndNamed) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("oscilab-jack-db-" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  EXPECT_EQ(damaged_jack_metadata(folder.string()), "");  // no folder: nothing to see
  std::filesystem::create_directories(folder);
  for (const char* name : {"__db.001", "__db.002", "metadata.db"}) {
    std::ofstream(folder / name) << std::string(4096, 'x');
  }
  EXPECT_EQ(damaged_jack_metadata(folder.string()), "");  // a sound database
  std::ofstream(folder / "__db.003").close();             // its region file left empty
  EXPECT_EQ(damaged_jack_metadata(folder.string()),
            "JACK's metadata database " + folder.string() +
                " is damaged (__db.003 is empty, as a JACK program killed while opening it "
                "leaves it): remove that folder while no JACK program runs");
  std::filesystem::remove_all(folder);
  EXPECT_EQ(jack_metadata_folder(), "/dev/shm/jack_db-" + std::to_string(::getuid()));
}

}  // namespace
}  // namespace oscilab::daq
