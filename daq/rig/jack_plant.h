#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "analysis/model/model.h"
#include "daq/jack/jack_client.h"
#include "daq/rig/shaker_plant.h"

struct _jack_client;  // libjack's jack_client_t (jack/types.h), kept out of this header
struct _jack_port;    // libjack's jack_port_t

namespace oscilab::daq {

/// A shaker with the oscillator on its table as a JACK client, in real time: what a drive (or
/// Oscilab's sine controller) sees of a real rig, through real JACK ports. It reads the drive on
/// its input port `drive` and writes the accelerometer and the vibrometer on its output ports
/// `acceleration` and `position`, in the ports' units: value = SI quantity / scale (the scales a
/// sidecar gives its channels). Each sample of the server's period is one ShakerPlant step, in
/// JACK's process callback (no allocation, lock or system call there).
///
/// Thread-safety: start/stop from one thread; the counters from any.
class JackPlant {
 public:
  struct Options {
    std::string server;  // empty: the default server
    std::string client_name = "oscilab-plant";
    bool positive_well = true;
    ShakerSpec shaker;
    SensorSpec sensors;
    double acceleration_scale_m_s2 = 50.0;  // m/s² per unit of the port (±50 m/s² full scale)
    double position_scale_m = 0.1;          // m per unit of the port
    int substeps = 1;                       // RK4 steps per sample
    std::uint64_t seed = 1;
  };

  /// Throws InputError naming the field when the options are invalid.
  JackPlant(const analysis::Model& model, Options options);
  ~JackPlant();
  JackPlant(const JackPlant&) = delete;
  JackPlant& operator=(const JackPlant&) = delete;

  /// Opens the client on the server (never starting one), registers the ports, builds the plant
  /// at the server's rate and activates. Returns "" or why not, naming the server.
  std::string start();
  void stop();

  /// "CLIENT:drive", "CLIENT:acceleration", "CLIENT:position" (the client's actual name).
  std::string port_name(const std::string& short_name) const;
  double rate_hz() const { return rate_hz_; }
  std::uint64_t frames() const { return frames_.load(std::memory_order_acquire); }
  /// The relative displacement z at the end of the last period (the truth, for tests).
  double z_m() const { return z_m_.load(std::memory_order_acquire); }
  bool shut_down() const { return shutdown_.happened(); }

  int process(std::uint32_t frames);
  void on_shutdown() { shutdown_.report(); }

 private:
  analysis::Model model_;
  Options options_;
  std::unique_ptr<ShakerPlant> plant_;
  _jack_client* client_ = nullptr;
  _jack_port* drive_port_ = nullptr;
  _jack_port* acceleration_port_ = nullptr;
  _jack_port* position_port_ = nullptr;
  double rate_hz_ = 0.0;
  std::atomic<std::uint64_t> frames_{0};
  std::atomic<double> z_m_{0.0};
  JackShutdown shutdown_;
};

}  // namespace oscilab::daq
