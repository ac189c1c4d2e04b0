// The shaker drive (daq/drive/) on the JACK plant (daq/rig/jack_plant.h): a real jackd (dummy
// backend, 48 kHz, period 256), the plant playing the paper's oscillator on a shaker, the drive
// closing the loop through JACK ports.
//   - settling: a stepped sine of 11 levels (f0 0.2 to 2.7 N at 9 Hz, ramps of 1 s); counters are
//     the whole cycles from each ramp's end to the first cycle within ±1 % (median, largest) and
//     how many levels came on target;
//   - CPU: the controller's step and the plant's step per sample, in-process (ns per sample).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>

#include "analysis/model/reference_models.h"
#include "daq/drive/jack_drive_client.h"
#include "daq/rig/jack_plant.h"
#include "daq/rig/shaker_plant.h"
#include "tests/daq/jack/jack_test_server.h"

namespace {

using namespace oscilab;
using namespace oscilab::daq;

void BM_DriveSettlingOnJackPlant(benchmark::State& state) {
  const analysis::Model model = analysis::paper_model();
  std::vector<double> cycles;
  int on_target = 0, levels = 0;
  for (auto _ : state) {
    testing::JackTestServer server(48000, 256);
    JackPlant::Options plant_options;
    plant_options.server = server.name();
    JackPlant plant(model, plant_options);
    if (!plant.start().empty()) state.SkipWithError("plant did not start");
    JackDriveClient::Options options;
    options.server = server.name();
    options.drive_port = plant.port_name("drive");
    options.acceleration_port = plant.port_name("acceleration");
    options.position_port = plant.port_name("position");
    options.acceleration_scale_m_s2 = plant_options.acceleration_scale_m_s2;
    options.position_scale_m = plant_options.position_scale_m;
    options.controller.gain_guess_m_s2_per_fs = 63.0;
    JackDriveClient drive(options);
    if (!drive.start().empty()) state.SkipWithError("drive did not start");
    for (int k = 0; k <= 10; ++k) {
      const double f0_n = 0.2 + 0.25 * k;
      (void)drive.take_events();
      (void)drive.set_level(f0_n / model.mass_kg(), 9.0);
      ++levels;
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      bool got = false;
      while (!got && std::chrono::steady_clock::now() < deadline) {
        for (const TimedDriveEvent& event : drive.take_events()) {
          if (event.event.state == DriveState::OnTarget && !got) {
            cycles.push_back(event.event.cycles);
            ++on_target;
            got = true;
          }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    }
    (void)drive.ramp_down();
    std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  }
  std::sort(cycles.begin(), cycles.end());
  state.counters["levels"] = levels;
  state.counters["levels_on_target"] = on_target;
  if (!cycles.empty()) {
    state.counters["median_cycles_to_1pct"] = cycles[cycles.size() / 2];
    state.counters["max_cycles_to_1pct"] = cycles.back();
  }
}
BENCHMARK(BM_DriveSettlingOnJackPlant)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// One sample of the controller, fed a table acceleration that follows its drive (a static plant
// of 42 m/s² per full scale): ns per sample; × 48 000 / 10⁹ is its share of a core at 48 kHz.
void BM_SineControllerStep(benchmark::State& state) {
  SineControllerOptions options;
  options.gain_guess_m_s2_per_fs = 63.0;
  SineController controller(options);
  controller.set_level(1.5 / 0.26, 9.0);
  double drive = 0.0, position_m = 0.027;
  for (auto _ : state) {
    drive = controller.step(42.0 * drive, position_m);
    benchmark::DoNotOptimize(drive);
  }
}
BENCHMARK(BM_SineControllerStep);

// One sample of the plant (the paper's model on the shaker, one RK4 step): ns per sample.
void BM_ShakerPlantStep(benchmark::State& state) {
  ShakerPlant plant(analysis::paper_model(), true, {}, {}, 48000.0, 1, 1);
  double k = 0.0;
  for (auto _ : state) {
    const SensorChain::Reading reading = plant.step(0.1 * std::sin(k));
    benchmark::DoNotOptimize(reading);
    k += 2.0 * 3.141592653589793 * 9.0 / 48000.0;
  }
}
BENCHMARK(BM_ShakerPlantStep);

}  // namespace

BENCHMARK_MAIN();
