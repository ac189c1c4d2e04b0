// The JACK capture client against a real jackd (dummy backend): a ring nobody drains fills, and
// the real-time callback drops the frames it has no room for and counts them.
#include "daq/jack/jack_capture_client.h"

#include <chrono>
#include <cstdint>
#include <thread>

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

}  // namespace
}  // namespace oscilab::daq
