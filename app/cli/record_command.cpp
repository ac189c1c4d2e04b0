// `oscilab-cli record --source rig|net:HOST:PORT|jack:PORT,PORT|file:REC --out REC [--duration S]`
// (contract §2):
// records a live source as it arrives, with its sidecar and event log, and prints the live EDC.
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "analysis/edc/level_tracker.h"
#include "app/cli/commands.h"
#include "app/cli/live_source_options.h"
#include "app/cli/output_files.h"
#include "app/cli/status_log.h"
#include "daq/live/acquisition.h"

namespace oscilab::cli {
namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void on_signal(int) { g_interrupted.store(true); }

struct RecordOptions {
  std::string source = "rig";
  std::string out;
  std::string edc;
  LiveSourceOptions live;
  double wait_s = 0.0;  // net: give up when no sender came within this (0: wait forever)
  int sync_ms = 1000;   // the recording goes to the disk at most this often
  std::string status_log;
  double status_every_s = 1.0;
};

// The status line: redrawn in place on a terminal (`final_line` false), or once at the end.
void print_status(std::FILE* out, const daq::AcquisitionStatus& s, bool final_line) {
  std::fprintf(
      out,
      "%s%s  t %.1f s  samples %llu  gaps %llu (%llu samples)  dup %llu  reord %llu  "
      "late %llu  nan %llu  sat %llu  overflow %llu  queue %zu/%zu  cycles %ld (-%ld)  "
      "levels %zu%s",
      final_line ? "" : "\r", s.source.c_str(), s.stream_time_s,
      static_cast<unsigned long long>(s.samples), static_cast<unsigned long long>(s.gaps),
      static_cast<unsigned long long>(s.gap_samples), static_cast<unsigned long long>(s.duplicates),
      static_cast<unsigned long long>(s.reordered), static_cast<unsigned long long>(s.late),
      static_cast<unsigned long long>(s.non_finite_samples),
      static_cast<unsigned long long>(s.saturated_samples),
      static_cast<unsigned long long>(s.overflowed_blocks), s.queue_fill, s.queue_capacity,
      s.cycles, s.excluded_cycles, s.levels, final_line ? "\n" : "   ");
}

// The live EDC table, complete under a temporary name before it takes its own.
void write_edc(const std::vector<analysis::LevelResult>& levels, const std::string& path) {
  write_output_file(path, [&](std::ostream& out) {
    out << "well,f0_n,edc_mean_j,edc_std_j,cycles,flags\n";
    char row[256];
    for (const auto& l : levels) {
      std::snprintf(row, sizeof row, "%s,%.9g,%.9g,%.9g,%d,", to_string(l.well).c_str(), l.f0_n,
                    l.edc_mean_j, l.edc_std_j, l.cycles);
      out << row << l.flags() << '\n';
    }
  });
}

void run(const RecordOptions& o) {
  std::signal(SIGINT, on_signal);  // first: a signal while setting up still ends cleanly
  std::signal(SIGTERM, on_signal);
  daq::AcquisitionOptions acquisition_options;
  if (o.sync_ms < 0) throw InputError("--sync-ms " + std::to_string(o.sync_ms) + ": must be >= 0");
  // 0 waits for a sender as long as it takes; a negative or non-finite wait is a mistake.
  if (!(o.wait_s >= 0.0) || !std::isfinite(o.wait_s)) {
    char text[120];
    std::snprintf(text, sizeof text, "--wait: %g s must be >= 0 (0: no limit)", o.wait_s);
    throw InputError(text);
  }
  if (!(o.status_every_s >= 0.01 && o.status_every_s <= 86400.0)) {
    char text[120];
    std::snprintf(text, sizeof text, "--status-every: %g s must be 0.01 to 86400",
                  o.status_every_s);
    throw InputError(text);
  }
  if (!o.status_log.empty() && o.status_log == o.out) {
    throw InputError("--status-log: " + o.status_log + " is the recording (--out)");
  }
  acquisition_options.recorder_sync_interval = std::chrono::milliseconds(o.sync_ms);
  auto acquisition = std::make_unique<daq::Acquisition>(make_live_source(o.source, o.live, true),
                                                        acquisition_options);
  // Recorded from the stream's first sample: at once for the rig and a replay, from the first
  // sender's first block for a network source (InputError here: a bad path or container).
  // The log is opened first (a bad --status-log writes nothing) and removed when the recording
  // cannot start.
  StatusLog status_log(o.status_log, o.status_every_s);
  try {
    acquisition->start_recording(o.out);
  } catch (...) {
    status_log.discard();
    throw;
  }
  std::printf("recording %s from %s\n", o.out.c_str(), acquisition->source().describe().c_str());
  std::fflush(stdout);
  acquisition->start();
  // The live status line is for a person watching: drawn only when stderr is a terminal.
  const bool terminal = isatty(STDERR_FILENO) != 0;
  const auto started = std::chrono::steady_clock::now();
  auto last_print = started;
  while (!g_interrupted.load() && !acquisition->finished()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const daq::AcquisitionStatus status = acquisition->status();
    if (!status.layout_known && o.wait_s > 0 &&
        std::chrono::steady_clock::now() - started > std::chrono::duration<double>(o.wait_s)) {
      acquisition->stop();
      // A sender that came but was refused is said with the reason, not as no sender at all.
      std::string refused;
      for (const daq::StreamEvent& event : acquisition->events_since(0)) {
        if (event.kind == daq::EventKind::MalformedFrame ||
            event.kind == daq::EventKind::LayoutMismatch) {
          refused = event.text;
        }
      }
      status_log.discard();  // nothing was recorded: no file is left
      char waited[64];
      std::snprintf(waited, sizeof waited, "%g s", o.wait_s);
      throw InputError(o.source + (refused.empty()
                                       ? ": no sender connected within " + std::string(waited)
                                       : ": no usable sender within " + std::string(waited) +
                                             "; the last was refused: " + refused));
    }
    status_log.maybe_write(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), status);
    if (!status.recorder_error.empty()) break;
    if (o.live.duration_s && status.stream_time_s >= *o.live.duration_s) break;
    if (terminal && std::chrono::steady_clock::now() - last_print > std::chrono::seconds(1)) {
      print_status(stderr, status, false);
      last_print = std::chrono::steady_clock::now();
    }
  }
  acquisition->stop();
  const daq::AcquisitionStatus status = acquisition->status();
  status_log.maybe_write(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), status,
      true);
  if (terminal) std::fputc('\n', stderr);
  // A failed recording (a full disk) is the one line on stderr; what it holds opens as it is.
  if (!status.recorder_error.empty()) throw InputError(status.recorder_error);
  // The final counts are a result: they close the live line on a terminal, and otherwise go to
  // standard output with the rest, so that stderr (a log, a pipe) holds nothing but errors.
  print_status(terminal ? stderr : stdout, status, true);
  const auto levels = acquisition->levels();
  std::printf("recorded %s: %llu samples (%.1f s)%s\n", o.out.c_str(),
              static_cast<unsigned long long>(status.recorded_samples),
              static_cast<double>(status.recorded_samples) / std::max(status.sample_rate_hz, 1.0),
              g_interrupted.load() ? ", stopped by a signal" : "");
  if (!status.edc_message.empty()) std::printf("%s\n", status.edc_message.c_str());
  std::printf(
      "live EDC: %zu level(s), %ld cycle(s), %ld excluded; latency last %.0f ms, max %.0f ms\n",
      levels.size(), status.cycles, status.excluded_cycles, 1e3 * status.edc_latency_s,
      1e3 * status.edc_latency_max_s);
  for (const auto& l : levels) {
    std::printf("  %-8s f0 %.3f N  EDC %.6g ± %.2g mJ  %d cycles %s\n", to_string(l.well).c_str(),
                l.f0_n, 1e3 * l.edc_mean_j, 1e3 * l.edc_std_j, l.cycles, l.flags().c_str());
  }
  // What the degenerate-data flags mean, once each (as analyze's report says them).
  for (const std::string& note : analysis::degenerate_level_notes(levels)) {
    std::printf("note: %s\n", note.c_str());
  }
  if (!o.edc.empty()) write_edc(levels, o.edc);
  status_log.throw_if_failed();
}

}  // namespace

void add_record_command(CLI::App& app) {
  auto o = std::make_shared<RecordOptions>();
  CLI::App* command = app.add_subcommand(
      "record",
      "Record a live source as it arrives (crash-safe): samples, sidecar and event log; print "
      "the live EDC per level");
  command
      ->add_option("--source", o->source,
                   "rig (the virtual rig in real time) | net:HOST:PORT (listen for a sender; "
                   "HOST 127.0.0.1 keeps it local) | jack:PORT_BASE,PORT_MASS[,...] (JACK "
                   "capture ports, one per --sidecar channel) | file:REC (replay a recording)")
      ->capture_default_str();
  command->add_option("--out", o->out, "recording to write: .wav, .w64 or .rf64")->required();
  command->add_option("--duration", o->live.duration_s,
                      "stop after this many seconds of stream (default: when the source ends, or "
                      "on SIGINT/SIGTERM)");
  command->add_option("--edc", o->edc, "write the live EDC table (CSV) here");
  command->add_option("--wait", o->wait_s, "net: fail when no sender came within S seconds");
  command
      ->add_option("--sync-ms", o->sync_ms,
                   "hand the samples and the event log to the disk (fdatasync) at most every N "
                   "ms; 0: after every block")
      ->capture_default_str();
  command->add_option("--status-log", o->status_log,
                      "write the acquisition's status here (CSV), a row every --status-every "
                      "seconds of wall time: stream time, counters, queue fill, live EDC latency");
  command
      ->add_option("--status-every", o->status_every_s,
                   "seconds of wall time between two rows of --status-log (0.01 to 86400)")
      ->capture_default_str();
  add_live_source_options(*command, o->live, true);
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
