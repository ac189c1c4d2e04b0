// `oscilab-cli plant --model paper|MODEL.json [--jack-server NAME]` (contract §2): the shaker with
// the oscillator on its table as a JACK client in real time (daq/rig/jack_plant.h), to try a
// drive, the sine controller or a recording chain without a rig: it reads its port `drive` and
// writes `acceleration` and `position` until SIGINT, SIGTERM or --duration.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>

#include "analysis/common/input_error.h"
#include "analysis/common/job.h"
#include "analysis/model/model_json.h"
#include "app/cli/commands.h"
#include "app/cli/option_parsing.h"
#include "daq/rig/jack_plant.h"

namespace oscilab::cli {
namespace {

CancelToken g_plant_cancel;
extern "C" void on_plant_signal(int) { g_plant_cancel.cancel(); }

struct PlantOptions {
  std::string model = "paper";
  std::string well = "positive";
  double duration_s = 0.0;
  daq::JackPlant::Options plant;
};

void run(PlantOptions o) {
  o.plant.positive_well = o.well == "positive";
  const analysis::Model model = analysis::model_from_spec(o.model);
  if (const std::string why = o.plant.shaker.validate(); !why.empty()) throw InputError(why);
  daq::JackPlant plant(model, o.plant);
  if (const std::string why = plant.start(); !why.empty())
    throw InputError("--jack-server: " + why);
  std::printf(
      "plant running at %.0f Hz: drive in %s, accelerometer out %s (%g m/s² per unit), "
      "vibrometer out %s (%g m per unit)\n",
      plant.rate_hz(), plant.port_name("drive").c_str(), plant.port_name("acceleration").c_str(),
      o.plant.acceleration_scale_m_s2, plant.port_name("position").c_str(),
      o.plant.position_scale_m);
  std::fflush(stdout);
  std::signal(SIGINT, on_plant_signal);
  std::signal(SIGTERM, on_plant_signal);
  const auto start = std::chrono::steady_clock::now();
  while (!g_plant_cancel.cancelled() && !plant.shut_down()) {
    if (o.duration_s > 0.0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
            o.duration_s) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const bool server_gone = plant.shut_down();
  const double seconds = static_cast<double>(plant.frames()) / plant.rate_hz();
  plant.stop();
  if (server_gone) throw InputError("--jack-server: the JACK server shut down");
  std::printf("plant stopped after %.1f s of the server's clock\n", seconds);
}

}  // namespace

void add_plant_command(CLI::App& app) {
  auto o = std::make_shared<PlantOptions>();
  CLI::App* command = app.add_subcommand(
      "plant",
      "Run a shaker with the model on its table as a JACK client in real time (reads the port "
      "drive, writes acceleration and position), to try a drive without a rig");
  command->add_option("--model", o->model, "paper, illustrative or a model JSON file")
      ->capture_default_str();
  command->add_option("--well", o->well, "the well the mass starts in")
      ->check(CLI::IsMember({"positive", "negative"}))
      ->capture_default_str();
  command->add_option("--jack-server", o->plant.server, "JACK server name (default: the default)");
  command->add_option("--client-name", o->plant.client_name, "the plant's JACK client name")
      ->capture_default_str();
  command
      ->add_option("--duration", o->duration_s,
                   "stop after this many seconds (0: at SIGINT or SIGTERM)")
      ->check(CLI::Range(0.0, 864000.0))
      ->capture_default_str();
  command->add_option("--table-mass", o->plant.shaker.table_mass_kg, "shaker table mass, kg")
      ->check(positive_number())
      ->capture_default_str();
  command
      ->add_option("--suspension-hz", o->plant.shaker.suspension_hz,
                   "natural frequency of the table on its suspension, Hz")
      ->check(positive_number())
      ->capture_default_str();
  command
      ->add_option("--suspension-damping", o->plant.shaker.suspension_damping_ratio,
                   "damping ratio of the suspension")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  command
      ->add_option("--force-per-fs", o->plant.shaker.force_n_per_fs,
                   "force on the table per unit of drive (amplifier and coil), N")
      ->check(positive_number())
      ->capture_default_str();
  command
      ->add_option("--acceleration-scale", o->plant.acceleration_scale_m_s2,
                   "m/s² per unit of the acceleration port")
      ->check(positive_number())
      ->capture_default_str();
  command
      ->add_option("--position-scale", o->plant.position_scale_m, "m per unit of the position port")
      ->check(positive_number())
      ->capture_default_str();
  command->add_option("--substeps", o->plant.substeps, "RK4 steps per sample")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--seed", o->plant.seed, "seed of the sensors' noise")->capture_default_str();
  command->callback([o] { run(*o); });
}

}  // namespace oscilab::cli
