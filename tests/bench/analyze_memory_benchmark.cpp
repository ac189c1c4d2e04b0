// Peak memory of the offline analysis against the record's length (target: a day-long record,
// 44 M samples per channel at 512 Hz, analysed within 150 MB and in time linear in its length).
// Each case analyses a virtual-rig stepped sine (26 levels of the paper's grid, the hold
// stretched to the record's length, 24-bit FLAC as `record` writes it) in a child process, whose
// peak resident set the kernel reports (wait4): the streamed analysis that `analyze` runs (the
// samples left in the file, no motion or cycles kept), and beside it, as the reference, the same
// recording read whole into memory with everything kept (what `fit`, `diagnose`, the app and
// Python hold). The argument is the record's length in minutes; ctest runs 10 and 60, and
// scripts/memory_study.sh the 6 h and 24 h records too.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>

#include <benchmark/benchmark.h>

#include "analysis/model/reference_models.h"
#include "analysis/pipeline/offline_analysis.h"
#include "daq/recording/campaign_reader.h"
#include "daq/recording/measurement_mapping.h"
#include "daq/recording/recording.h"
#include "daq/rig/virtual_rig.h"

namespace {

using namespace oscilab;

struct ChildRun {
  double peak_rss_mb = 0.0;
  double wall_s = 0.0;
  bool ok = false;
};

// Runs `work` in a child process: its peak resident set and wall time. The child exits without
// running destructors (nothing of it needs to outlive the measurement).
ChildRun in_child(const std::function<void()>& work) {
  std::fflush(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    try {
      work();
    } catch (const std::exception& error) {
      std::fprintf(stderr, "analyze_memory_benchmark: %s\n", error.what());
      _exit(1);
    }
    _exit(0);
  }
  int status = 0;
  rusage usage{};
  ChildRun run;
  if (pid < 0 || wait4(pid, &status, 0, &usage) != pid) return run;
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.peak_rss_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss in KiB
  run.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return run;
}

// The rig's record of `minutes`, written once per process into a temporary directory (made in a
// child too, so that this process stays small and its children start from the same footprint).
std::string record_of(int minutes) {
  static std::map<int, std::string> made;
  if (auto it = made.find(minutes); it != made.end()) return it->second;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("oscilab_memory_bench_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / ("stepped_" + std::to_string(minutes) + "min.flac")).string();
  const ChildRun written = in_child([&] {
    analysis::SteppedSineSchedule schedule;
    for (int i = 0; i < 26; ++i) schedule.levels_n.push_back(0.2 + 0.1 * i);
    schedule.hold_s = (60.0 * minutes - schedule.lead_in_s) / 26.0;
    daq::RigSpec spec;
    spec.seed = 1;
    daq::write_recording(
        daq::record_stepped_sine(analysis::paper_model(), schedule, spec).recording, path);
  });
  if (!written.ok) return "";
  made[minutes] = path;
  return path;
}

// Analyses the rig's record of state.range(0) minutes with `analyse` in a child process and
// reports its peak memory against the signal's size.
void measure(benchmark::State& state,
             const std::function<analysis::CampaignAnalysis(const std::string&)>& analyse) {
  const int minutes = static_cast<int>(state.range(0));
  const std::string path = record_of(minutes);
  if (path.empty()) return state.SkipWithError("the virtual rig's record could not be written");
  ChildRun run;
  for (auto _ : state) {
    run = in_child([&] {
      const analysis::CampaignAnalysis campaign = analyse(path);
      if (!campaign.stiffness) throw std::runtime_error(campaign.rfs_message);
    });
  }
  if (!run.ok) return state.SkipWithError("the analysis failed in its child process");
  const double signal_mb = 60.0 * minutes * 512.0 * 2 * 8 / (1024.0 * 1024.0);  // 2 ch, double
  state.counters["peak_rss_MB"] = run.peak_rss_mb;
  state.counters["signal_MB"] = signal_mb;
  state.counters["rss_per_signal"] = run.peak_rss_mb / signal_mb;
  state.counters["analysis_s"] = run.wall_s;
}

// `analyze`'s path: the samples streamed from the file, neither motion nor cycles kept.
void BM_AnalyzeStreamed(benchmark::State& state) {
  measure(state, [](const std::string& path) {
    analysis::OfflineRetention retention;
    retention.cycles = false;
    retention.motion = false;
    return analysis::analyze_campaign(daq::open_campaign_streamed({path}, {}),
                                      analysis::PipelineSettings{}, {}, {}, retention);
  });
}

// The reference: the recording read whole, everything kept.
void BM_AnalyzeInMemory(benchmark::State& state) {
  measure(state, [](const std::string& path) {
    return analysis::analyze_campaign(daq::read_campaign({path}, {}), analysis::PipelineSettings{});
  });
}

// The record lengths, one run each: a run is seconds to a minute, and its peak memory does not
// vary between runs.
void record_lengths(benchmark::internal::Benchmark* lengths) {
  lengths->Arg(10)->Arg(60)->Arg(360)->Arg(1440)->Iterations(1)->UseRealTime();
  lengths->Unit(benchmark::kSecond);
}
BENCHMARK(BM_AnalyzeStreamed)->Apply(record_lengths);
BENCHMARK(BM_AnalyzeInMemory)->Apply(record_lengths);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ignored;
  std::filesystem::remove_all(
      std::filesystem::temp_directory_path() / ("oscilab_memory_bench_" + std::to_string(getpid())),
      ignored);
  return 0;
}
