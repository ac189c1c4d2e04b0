#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/common/time_interval.h"
#include "analysis/edc/level_tracker.h"
#include "analysis/pipeline/channel_source.h"
#include "analysis/signal/motion_quantity.h"

namespace oscilab::analysis {

/// The analysis's view of one recording: the two motion channels in SI, and what the sidecar
/// says about the excitation. Built from a recording by daq/ (measurement_channels()). The
/// samples are either in memory (base, mass) or streamed from their file (source: base and mass
/// stay empty), which the offline analysis reads a pass at a time in bounded memory.
struct MeasurementChannels {
  std::string name;  // for messages and tables, e.g. the file name
  double sample_rate_hz = 0.0;
  std::optional<double> mass_kg;  // unknown: energies are reported per unit mass
  Eigen::VectorXd base;           // table motion
  MotionQuantity base_quantity = MotionQuantity::Acceleration;
  Eigen::VectorXd mass;  // mass motion (absolute y), or z itself when mass_is_relative
  MotionQuantity mass_quantity = MotionQuantity::Displacement;
  bool mass_is_relative = false;
  std::string excitation_type;  // "stepped-sine", "random", or "" (unknown: detect)
  std::optional<double> excitation_freq_hz;
  std::vector<LevelWindow> level_windows;  // steady parts of the holds, when the sidecar has them
  std::optional<bool> well_hint_positive;
  /// Stretches not to trust (the sidecar's invalid intervals): samples there may be non-finite;
  /// cycles touching them are left out, and restoring-force samples near them too.
  std::vector<TimeInterval> excluded;
  std::shared_ptr<const ChannelSource> source;  // set: the samples stay in their file

  /// Samples per channel, wherever they are.
  Eigen::Index sample_count() const { return source ? source->sample_count() : base.size(); }
  /// A pass over the samples from the first on (the source's, or over base and mass).
  std::unique_ptr<ChannelReader> open() const {
    if (source) return source->open();
    return std::make_unique<MemoryChannelReader>(base.data(), mass.data(), base.size());
  }
};

}  // namespace oscilab::analysis
