// `oscilab-cli stream REC|rig --to HOST:PORT [--speed X]` (contract §2): plays a recording or the
// live virtual rig to a listening Oscilab in the stream protocol (docs/stream-protocol.md).
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "analysis/common/job.h"
#include "app/cli/commands.h"
#include "app/cli/live_source_options.h"
#include "daq/network/stream_sender.h"
#include "daq/network/tcp_socket.h"

namespace oscilab::cli {
namespace {

CancelToken g_stream_cancel;  // SIGINT and SIGTERM end the stream cleanly (a BYE)
extern "C" void on_stream_signal(int) { g_stream_cancel.cancel(); }

struct StreamOptions {
  std::string input = "rig";
  std::string to;
  double retry_s = 10.0;
  LiveSourceOptions live;
};

void run(const StreamOptions& o) {
  daq::StreamSender::Options options;
  daq::parse_host_port(o.to, "--to", options.host, options.port);
  options.retry_s = o.retry_s;
  std::unique_ptr<daq::SampleSource> source = make_live_source(o.input, o.live, false);
  daq::StreamSender sender(options);
  std::signal(SIGINT, on_stream_signal);
  std::signal(SIGTERM, on_stream_signal);
  std::signal(SIGPIPE, SIG_IGN);
  const daq::StreamSender::Result result = sender.run(*source, {}, g_stream_cancel);
  using Status = daq::StreamSender::Status;
  if (result.status == Status::NoReceiver) throw InputError(result.message);
  if (result.status == Status::ReceiverGone) throw InputError("--to " + result.message);
  const daq::StreamSender::Counters& c = result.counters;
  std::printf("streamed %llu block(s) to %s, %llu lost while reconnecting (%llu reconnection(s))\n",
              static_cast<unsigned long long>(c.blocks_sent), o.to.c_str(),
              static_cast<unsigned long long>(c.blocks_lost),
              static_cast<unsigned long long>(c.reconnections));
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
