#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

namespace oscilab::daq {

/// A block of samples exactly as a source delivers them: stored values (before calibration, as
/// the stream's sidecar describes them), row-major, one row per sample time. `first_sample`
/// places the block on the stream's sample clock (t = first_sample / rate), and `sequence`
/// numbers blocks consecutively from 0, so that a consumer detects dropped, repeated and
/// reordered blocks. Storage is sized once (BlockQueue) and reused: filling a block never
/// allocates while rows × channels stays within its capacity.
struct RawBlock {
  std::uint64_t sequence = 0;
  std::uint64_t first_sample = 0;
  int rows = 0;
  int channels = 0;
  std::vector<double> values;  // rows × channels used; capacity fixed by the queue
  /// When the source handed the block over (steady clock): latency is measured from here.
  std::chrono::steady_clock::time_point delivered;

  double value(int row, int channel) const {
    return values[static_cast<std::size_t>(row) * static_cast<std::size_t>(channels) +
                  static_cast<std::size_t>(channel)];
  }
};

}  // namespace oscilab::daq
