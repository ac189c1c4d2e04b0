// `oscilab-cli stream REC|rig --to HOST:PORT [--speed X]` (contract §2): plays a recording or the
// live virtual rig to a listening Oscilab in the stream protocol (docs/stream-protocol.md).
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "app/cli/commands.h"
#include "app/cli/live_source_options.h"
#include "daq/live/block_queue.h"
#include "daq/live/stream_protocol.h"
#include "daq/live/tcp_socket.h"

namespace oscilab::cli {
namespace {

std::atomic<bool> g_stream_interrupted{false};
extern "C" void on_stream_signal(int) { g_stream_interrupted.store(true); }

struct StreamOptions {
  std::string input = "rig";
  std::string to;
  double retry_s = 10.0;
  LiveSourceOptions live;
};

// Events the receiver needs to analyse and record the stream as operated.
bool forwarded(const std::string& kind) {
  return kind == "level" || kind == "mark" || kind == "discontinuity" || kind == "invalid";
}

void run(const StreamOptions& o) {
  std::string host;
  std::uint16_t port = 0;
  daq::parse_host_port(o.to, "--to", host, port);
  std::unique_ptr<daq::SampleSource> source = make_live_source(o.input, o.live, false);
  daq::stream_protocol::Hello hello;
  hello.sidecar = *source->layout();
  std::random_device entropy;
  hello.stream_id = "oscilab-" + std::to_string(entropy()) + std::to_string(entropy());
  daq::BlockQueue queue(256, source->max_block_rows(), source->max_channels());

  daq::TcpSocket socket = daq::TcpSocket::connect_to(host, port);
  std::vector<std::uint8_t> frame;
  daq::stream_protocol::append_hello(hello, frame);
  std::signal(SIGINT, on_stream_signal);
  std::signal(SIGTERM, on_stream_signal);
  std::signal(SIGPIPE, SIG_IGN);
  source->start(queue);
  std::uint64_t sent_blocks = 0, lost_blocks = 0, reconnections = 0;
  const auto send = [&](const std::vector<std::uint8_t>& bytes) {
    if (socket.valid() && socket.send_all(bytes.data(), bytes.size())) return true;
    // The receiver went away: try again for up to --retry seconds, same stream_id, so that it
    // sees what was lost meanwhile as a gap.
    socket.close();
    const auto give_up =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(o.retry_s);
    while (!g_stream_interrupted.load() && std::chrono::steady_clock::now() < give_up) {
      try {
        socket = daq::TcpSocket::connect_to(host, port);
        std::vector<std::uint8_t> greeting;
        daq::stream_protocol::append_hello(hello, greeting);
        if (socket.send_all(greeting.data(), greeting.size())) {
          ++reconnections;
          return false;  // this frame is lost; the next goes to the new connection
        }
      } catch (const InputError&) {
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    throw InputError("--to " + o.to + ": the receiver is gone (no connection for " +
                     std::to_string(o.retry_s) + " s)");
  };
  send(frame);
  while (!g_stream_interrupted.load()) {
    // The block first, then the events: a source posts an event before it publishes the block
    // that reaches the event's time, so the receiver gets every event before its block.
    daq::RawBlock* block = queue.front();
    for (const daq::StreamEvent& event : source->take_events()) {
      if (!forwarded(event.kind)) continue;
      frame.clear();
      daq::stream_protocol::append_event(event, frame);
      send(frame);
    }
    if (block == nullptr) {
      if (source->finished() && queue.size() == 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    frame.clear();
    daq::stream_protocol::append_data(block->sequence, block->first_sample, block->rows,
                                      block->channels, block->values.data(), frame);
    queue.pop();
    ++(send(frame) ? sent_blocks : lost_blocks);
  }
  source->stop();
  frame.clear();
  daq::stream_protocol::append_bye(frame);
  if (socket.valid()) socket.send_all(frame.data(), frame.size());
  std::printf("streamed %llu block(s) to %s, %llu lost while reconnecting (%llu reconnection(s))\n",
              static_cast<unsigned long long>(sent_blocks), o.to.c_str(),
              static_cast<unsigned long long>(lost_blocks),
              static_cast<unsigned long long>(reconnections));
}

}  // namespace

void add_stream_command(CLI::App& app) {
  auto o = std::make_shared<StreamOptions>();
  CLI::App* command = app.add_subcommand(
      "stream",
      "Send a recording (or the live virtual rig) to a listening Oscilab in the stream protocol");
  command->add_option("INPUT", o->input, "a recording to play, or rig")->capture_default_str();
  command
      ->add_option("--to", o->to,
                   "HOST:PORT of the receiver (oscilab-cli record --source "
                   "net:HOST:PORT, or the app)")
      ->required();
  command
      ->add_option("--retry", o->retry_s,
                   "when the receiver goes away, try to reconnect for this many seconds")
      ->capture_default_str();
  command->add_option("--duration", o->live.duration_s, "rig: stop after this many seconds");
  add_live_source_options(*command, o->live, false);
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
