#pragma once

#include <cstdint>
#include <mutex>
#include <vector>

namespace oscilab::daq {

/// Decimated traces for display: per bucket the min and the max of each trace (an envelope, as
/// a scope draws), in time order; NaN where a derived trace is not computed (yet).
struct TraceHistory {
  std::vector<double> t_s;
  std::vector<double> base;     // b̈ (or the base channel's quantity), SI
  std::vector<double> mass;     // y (or the mass channel's quantity), SI
  std::vector<double> force_n;  // f = −m b̈
  std::vector<double> b_m, z_m, z_dot_m_s, restoring_force_n;  // derived, delayed
  void clear();
};

/// The last minutes of a live stream's traces, indexed by stream sample, for the display's
/// scroll-back: the measured traces (base, mass, f) as blocks arrive, the derived ones (b, z, ż,
/// R) a filter latency later.
///
/// The acquisition thread writes one block at a time under the ring's own lock (never the
/// acquisition's); readers thin it to an envelope under that lock. So that a reader showing ten
/// minutes does not hold the writer up while it scans them, the ring keeps the min and the max
/// of every chunk of kChunk samples as they are written, and a wide window is thinned from those
/// (work in proportion to the buckets, not the samples).
class HistoryRing {
 public:
  static constexpr std::uint64_t kChunk = 64;  // samples per min/max summary

  /// What one block writes: measured samples [measured_first, + measured_count) and derived
  /// samples [derived_first, + derived_count); a null trace is written as NaN.
  struct BlockWrite {
    std::uint64_t measured_first = 0;
    int measured_count = 0;
    const double *base = nullptr, *mass = nullptr, *force_n = nullptr;
    std::uint64_t derived_first = 0;
    int derived_count = 0;
    const double *b_m = nullptr, *z_m = nullptr, *z_dot_m_s = nullptr, *restoring_force_n = nullptr;
  };

  /// Keeps at least `capacity_samples` (rounded up to whole chunks).
  HistoryRing(std::uint64_t capacity_samples, double sample_rate_hz);

  /// One block's samples, under one lock. Measured samples continue the stream (first ≥ end());
  /// derived samples older than the ring keeps are dropped.
  void write(const BlockWrite& block);
  /// Samples [first, first + count) never arrived: NaN in every trace.
  void write_gap(std::uint64_t first, std::uint64_t count);

  /// One past the newest measured sample.
  std::uint64_t end() const;
  double sample_rate_hz() const { return rate_hz_; }
  /// Traces kept per sample, a double each: base, mass, f, b, z, ż, R.
  static constexpr int kTraces = 7;

  /// Traces over [from_s, to_s] (stream time) thinned to at most 2 × buckets points each: every
  /// sample when there are no more than `buckets`, else each bucket's min and max in the order
  /// they occur. Wide windows use buckets of whole chunks.
  void read(double from_s, double to_s, int buckets, TraceHistory& out) const;

 private:
  struct Summary {  // of one trace over one chunk
    double lo, hi;
    std::uint64_t lo_at, hi_at;
  };
  std::size_t slot(std::uint64_t sample) const {
    return static_cast<std::size_t>(sample % capacity_);
  }
  std::size_t chunk(std::uint64_t sample) const {
    return static_cast<std::size_t>((sample / kChunk) % chunks_);
  }
  /// The first sample whose chunk is still whole in the ring.
  std::uint64_t oldest() const;
  void put(int trace, std::uint64_t sample, double value);
  void start_chunk(std::uint64_t sample);  // a chunk slot gets its new samples

  const std::uint64_t capacity_;  // samples, a whole number of chunks
  const std::size_t chunks_;
  const double rate_hz_;
  mutable std::mutex mutex_;
  std::uint64_t end_ = 0;
  std::vector<double> traces_[kTraces];
  std::vector<Summary> summaries_[kTraces];  // per chunk slot
  std::vector<std::uint64_t> chunk_first_;   // the first sample of the chunk each slot holds
};

}  // namespace oscilab::daq
