// CPU of the JACK path: a real jackd (dummy backend, 48 kHz, period 256) with a test client
// playing two sines, JackSource (process callback, ring, soxr 48 kHz → 512 Hz), the acquisition
// (checks, EDC, derived traces) and the recorder, in one process.
//   - real time: CPU of the whole process (the test client's sines included; the server not)
//     per second of signal, in % of one core;
//   - freewheeling: signal seconds per wall second, and the CPU per second of signal;
//   - stop() of a source reconnecting to a server gone for good: seconds until it returns.
// Each figure is a counter of one run; repetitions give the medians.
#include <chrono>
#include <csignal>
#include <ctime>
#include <filesystem>
#include <thread>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include "daq/live/acquisition.h"
#include "tests/daq/sources/jack_test_helpers.h"

namespace {

using namespace oscilab::daq;
using namespace oscilab::daq::testing;

double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void run_jack(benchmark::State& state, bool freewheel) {
  const double signal_s = freewheel ? 120.0 : 5.0;
  for (auto _ : state) {
    JackTestServer server;
    JackTestPlayer player(server.name(), 2);
    player.play_sines({{0.5, 9.0, 0.0}, {0.25, 9.0, 1.0}});
    auto made = std::make_unique<JackSource>(jack_options(server, player));
    JackSource* source = made.get();
    Acquisition acquisition(std::move(made), {});
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("oscilab_bench_jack_" + std::to_string(::getpid()) + ".wav"))
                                 .string();
    acquisition.start_recording(path);
    acquisition.start();
    wait_for([&] { return source->counters().samples_delivered > 0; }, 10);
    const std::uint64_t first = source->counters().samples_delivered;
    const double cpu0 = process_cpu_s();
    const auto wall0 = Clock::now();
    if (freewheel) player.set_freewheel(true);
    const auto target = first + static_cast<std::uint64_t>(signal_s * kRateHz);
    wait_for([&] { return source->counters().samples_delivered >= target; }, 600);
    if (freewheel) player.set_freewheel(false);
    const double wall = std::chrono::duration<double>(Clock::now() - wall0).count();
    const double cpu = process_cpu_s() - cpu0;
    const double done_s =
        static_cast<double>(source->counters().samples_delivered - first) / kRateHz;
    acquisition.stop();
    state.counters["cpu_pct_per_signal_s"] = 100.0 * cpu / done_s;
    state.counters["x_real_time"] = done_s / wall;
    state.counters["xruns"] = static_cast<double>(acquisition.status().jack.xruns);
    for (const char* suffix : {".wav", ".json", ".events.jsonl"}) {
      std::filesystem::remove(std::filesystem::path(path).replace_extension("").string() + suffix);
    }
  }
}

void BM_JackRealTime48kHz(benchmark::State& state) { run_jack(state, false); }
BENCHMARK(BM_JackRealTime48kHz)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_JackFreewheel48kHz(benchmark::State& state) { run_jack(state, true); }
BENCHMARK(BM_JackFreewheel48kHz)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// How long stop() takes while the source waits for a server gone for good (the default
// reconnection interval, 0.5 s: a try in progress or the wait before the next one ends first).
void BM_JackStopWhileReconnecting(benchmark::State& state) {
  for (auto _ : state) {
    JackTestServer server;
    JackTestPlayer player(server.name(), 2);
    auto source = std::make_unique<JackSource>(jack_options(server, player));
    BlockQueue queue(256, source->max_block_rows(), 2);
    source->start(queue);
    wait_for([&] { return source->counters().samples_delivered > 0; }, 60);
    server.stop(SIGTERM);
    wait_for([&] { return source->counters().jack.failed_reconnects >= 2; }, 60);
    const auto stop0 = Clock::now();
    source->stop();
    state.counters["stop_s"] = std::chrono::duration<double>(Clock::now() - stop0).count();
  }
}
BENCHMARK(BM_JackStopWhileReconnecting)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
