#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "daq/sources/raw_block.h"

namespace oscilab::daq {

/// Why a sample is left out: it is not a number, or it reached its channel's range.
enum class BadSampleKind { NonFinite, Saturated };

/// "non-finite" | "saturated": the event kind and the invalid-interval reason.
const char* to_string(BadSampleKind kind);

/// Checks every stored value of a stream as it arrives: a value that is not finite, or whose
/// physical value scale × stored + offset reaches the channel's range, is bad. Consecutive bad
/// samples of one channel form a run, reported once when it ends (or at finish()), so that a
/// saturated stretch is one event and one invalid interval, not one per sample.
///
/// Not thread-safe: the acquisition thread's. check() allocates nothing while runs stay open or
/// the blocks are clean; a run that closes is appended to the caller's vector.
class SampleChecker {
 public:
  struct Channel {
    std::string name;
    double scale = 1.0, offset = 0.0;
    std::optional<std::pair<double, double>> range;  // in the channel's unit
  };
  /// A run of bad samples of one channel, closed: samples [from, to], `count` of them.
  struct Run {
    BadSampleKind kind = BadSampleKind::NonFinite;
    int channel = 0;
    std::uint64_t from = 0, to = 0, count = 0;
  };
  struct Counts {
    std::uint64_t non_finite = 0, saturated = 0;
  };

  SampleChecker() = default;
  SampleChecker(std::vector<Channel> channels, int max_rows);

  /// Checks the block's samples (stream samples first_sample ...). bad_row(r) then tells whether
  /// row r had a bad value in any channel; runs that ended are appended to `closed`.
  Counts check(const RawBlock& block, std::uint64_t first_sample, std::vector<Run>& closed);
  bool bad_row(int row) const { return bad_rows_[static_cast<std::size_t>(row)] != 0; }
  /// Closes every open run (the end of the stream).
  void finish(std::vector<Run>& closed);

  const std::vector<Channel>& channels() const { return channels_; }

 private:
  struct OpenRun {
    bool open = false;
    std::uint64_t from = 0, to = 0, count = 0;
  };
  void close(OpenRun& run, BadSampleKind kind, int channel, std::vector<Run>& closed);

  std::vector<Channel> channels_;
  std::vector<OpenRun> non_finite_, saturated_;  // per channel
  std::vector<char> bad_rows_;                   // of the last block
};

}  // namespace oscilab::daq
