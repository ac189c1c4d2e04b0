#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace oscilab::analysis {

/// A block of calibrated samples (SI) from one source, as the pipeline consumes them: column 0
/// the base channel, column 1 the mass channel, one row per sample at the stream's rate. The
/// sequence number lets a consumer detect dropped, repeated or reordered blocks.
struct SampleBlock {
  std::uint64_t sequence = 0;
  double t0_s = 0.0;        // time of the first row
  Eigen::MatrixXd samples;  // rows: samples; cols: base, mass
};

}  // namespace oscilab::analysis
