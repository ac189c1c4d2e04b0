#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "analysis/model/excitation_force.h"
#include "analysis/signal/motion_quantity.h"
#include "analysis/signal/streaming_integrator.h"

namespace oscilab::analysis {

/// The signals of eq. (1) derived from a stream of calibrated base and mass samples as they
/// arrive: the table's displacement b, the relative motion z = y − b and ż, and the restoring
/// force R = f − m z̈ = −m ÿ (or f − m z̈ when the mass channel measures z itself). Integrals
/// and derivatives come from StreamingIntegrator, the offline zero-phase band as a linear-phase
/// filter, so each derived value is that of the sample `latency_samples()` before the newest.
///
/// A value whose filter span touches an excluded sample (a fault: gap, non-finite, saturated,
/// discontinuity), or that comes before every filter is full, is NaN: the caller feeds zeros in
/// place of bad samples and says which they were with exclude().
///
/// Qt-free and reusable offline (feed a recording block by block). Not thread-safe: one
/// producer. push() never allocates.
class DerivedSignals {
 public:
  struct Options {
    double sample_rate_hz = 512.0;
    double mass_kg = 1.0;
    MotionQuantity base_quantity = MotionQuantity::Acceleration;
    MotionQuantity mass_quantity = MotionQuantity::Displacement;
    bool mass_is_relative = false;         // the mass channel measures z = y − b itself
    double integration_highpass_hz = 1.0;  // PipelineSettings::integration_highpass_hz
    double derivative_lowpass_hz = 0.0;    // PipelineSettings::derivative_lowpass_hz
    double latency_s = 2.0;
    int max_rows = 0;  // largest block push() is given (sizes the output)
  };
  /// One block of derived values: samples [first_sample, first_sample + count) of the stream.
  struct Block {
    std::uint64_t first_sample = 0;
    int count = 0;
    std::vector<double> b_m, z_m, z_dot_m_s, restoring_force_n;
  };

  explicit DerivedSignals(const Options& options);  // throws InputError on bad options
  ~DerivedSignals();
  DerivedSignals(const DerivedSignals&) = delete;
  DerivedSignals& operator=(const DerivedSignals&) = delete;

  int latency_samples() const { return latency_; }
  /// A block sized for `max_rows` inputs.
  Block make_block() const;

  /// Feeds samples first_sample … first_sample + rows − 1 (SI; zeros in place of bad samples)
  /// and writes the derived values they complete into `out` (count 0 while the filters fill).
  void push(std::uint64_t first_sample, const double* base_si, const double* mass_si, int rows,
            Block& out);
  /// Samples [from, to] are faults: derived values within the filters' reach of them are NaN.
  void exclude(std::uint64_t from, std::uint64_t to);

 private:
  Options options_;
  // b, ḃ, ẏ, ÿ, y (ż, z̈, z for a relative mass channel); null where the channel measures that
  // quantity already (its delayed sample is used).
  std::unique_ptr<StreamingIntegrator> filters_[5];
  int latency_ = 0;
  std::vector<double> delayed_base_, delayed_mass_;  // the last latency + 1 inputs
  bool fault_seen_ = false;
  std::uint64_t last_fault_ = 0;
};

}  // namespace oscilab::analysis
