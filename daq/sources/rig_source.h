#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "analysis/model/model.h"
#include "daq/rig/virtual_rig.h"
#include "daq/sources/sample_source.h"

namespace oscilab::daq {

/// One step of an unattended stepped sine: at stream time t_s, set f0 and ν.
struct ExcitationStep {
  double t_s = 0.0;
  double f0_n = 0.0;
  double frequency_hz = 9.0;
};

/// The schedule of an unattended stepped sine: at rest for `lead_in_s`, then each of `levels_n`
/// held `hold_s` at `frequency_hz`, then at rest again. Throws InputError unless hold_s > 0,
/// lead_in_s ≥ 0 and frequency_hz > 0.
std::vector<ExcitationStep> rig_schedule(const std::vector<double>& levels_n, double hold_s,
                                         double lead_in_s, double frequency_hz);

/// The virtual rig as a live source: the model on the shaking table integrated block by block in
/// real time (or faster), the accelerometer and vibrometer read at every sample (SensorChain),
/// stored as ADC counts. The operator sets and steps the forcing amplitude and frequency while it
/// runs (set_excitation); a schedule runs a whole stepped sine unattended. Every change is posted
/// as a `level` event with its steady window, so the recorder writes the excitation as operated.
class RigSource final : public SampleSource {
 public:
  struct Options {
    RigSpec rig;                // well, rate, sensors, seed, integration tolerances
    double frequency_hz = 9.0;  // ν until changed (§3.2)
    double ramp_s = 0.5;        // each change is ramped over this (C², table_motion.h)
    double speed = 1.0;         // × real time; 0: as fast as possible (tests, benchmarks)
    int block_rows = 16;        // samples per block (31 ms at 512 Hz)
    std::vector<ExcitationStep> schedule;  // in time order; applied as the stream reaches them
    std::optional<double> duration_s;      // the source ends there; none: until stopped
    /// Full scale of the ADC channels, in SI: samples are clipped there, as a real DAQ does,
    /// and the sidecar declares it (ChannelInfo::range), so saturation is detected.
    double accelerometer_range_m_s2 = 250.0;
    double vibrometer_range_m = 0.05;
  };

  /// Throws InputError on bad options (rate, speed, block size, schedule order).
  RigSource(analysis::Model model, Options options);
  ~RigSource() override;

  /// Operator: ramp to f0_n at frequency_hz from the next block on. Thread-safe.
  void set_excitation(double f0_n, double frequency_hz);
  /// The excitation set last (operator or schedule), for the display. Thread-safe.
  ExcitationStep excitation() const;

  int max_block_rows() const override { return options_.block_rows; }
  std::string describe() const override { return "virtual rig"; }

 private:
  void run() override;

  analysis::Model model_;
  Options options_;
  mutable std::mutex command_mutex_;
  std::optional<ExcitationStep> pending_;  // operator command, applied by the rig thread
  ExcitationStep current_{};
};

}  // namespace oscilab::daq
