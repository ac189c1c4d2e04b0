#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/signal/ac_coupling.h"
#include "analysis/signal/motion_quantity.h"
#include "daq/recording/sidecar.h"
#include "daq/sources/raw_block.h"

namespace oscilab::daq {

/// How the live chain turns a stream's stored values into the SI motion of eq. (1): the stream's
/// first base channel and its first mass channel (else its first relative one), each calibrated
/// as its sidecar says (physical = (scale × stored + offset) × the unit's factor to SI), with the
/// high-pass of an AC-coupled input undone (`ac_coupling_hz`, analysis/signal/ac_coupling.h),
/// and the excitation force f = −m b̈ where the base channel is an acceleration.
///
/// Thread-safety: one thread (calibrate() keeps the AC-coupling filters' state).
class StreamCalibration {
 public:
  /// One channel's stored value to SI.
  struct Channel {
    int index = -1;  // in the layout; -1: none
    double scale = 1.0, offset = 0.0, factor = 1.0;
    analysis::MotionQuantity quantity = analysis::MotionQuantity::Acceleration;
    double to_si(double stored) const { return (scale * stored + offset) * factor; }
  };

  /// One block's rows, calibrated (vectors of max_rows, allocated once).
  struct Rows {
    std::vector<double> base_si, mass_si;        // bad samples as 0: filters and fits stay finite
    std::vector<double> base_shown, mass_shown;  // bad samples as NaN: the display shows a hole
    std::vector<double> force_n;  // f = −m b̈; NaN unless the base is acceleration
  };

  /// Nothing analysed.
  StreamCalibration() = default;
  /// The channels of `layout` (throws InputError naming a channel with an unknown unit or a bad
  /// AC-coupling corner).
  explicit StreamCalibration(const Sidecar& layout);

  /// Whether the stream has a base and a mass (or relative) motion channel, neither a force.
  bool analysed() const { return base_.index >= 0 && mass_.index >= 0; }
  const Channel& base() const { return base_; }
  const Channel& mass() const { return mass_; }
  /// The mass channel is the relative motion z (no absolute mass channel in the stream).
  bool mass_relative() const { return mass_relative_; }
  double mass_kg() const { return mass_kg_; }

  /// A warning for each AC-coupled channel whose corner is within 10× of the excitation
  /// frequency (0: not known, no warning): there the corrected phase depends on how well the
  /// corner is known.
  std::vector<std::string> ac_coupling_warnings(double excitation_freq_hz) const;

  Rows make_rows(int max_rows) const;
  /// The block's rows into `rows` (analysed() only).
  void calibrate(const RawBlock& block, Rows& rows);

 private:
  std::vector<std::pair<std::string, double>> ac_corners_;  // AC-coupled: name, corner (Hz)
  Channel base_, mass_;
  bool mass_relative_ = false;
  double mass_kg_ = 1.0;
  // The AC-coupling high-pass of a channel, undone after calibration (sidecar ac_coupling_hz).
  std::optional<analysis::AcCouplingInverse> base_ac_, mass_ac_;
};

}  // namespace oscilab::daq
