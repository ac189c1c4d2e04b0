#include "daq/live/history_ring.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace oscilab::daq {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t kNoChunk = std::numeric_limits<std::uint64_t>::max();

// Running min and max of finite values, each at its first occurrence (strict comparisons).
struct Envelope {
  double lo = kNaN, hi = kNaN;
  std::uint64_t lo_at = 0, hi_at = 0;
  void add(double lo_value, std::uint64_t lo_sample, double hi_value, std::uint64_t hi_sample) {
    if (std::isfinite(lo_value) && !(lo_value >= lo)) lo = lo_value, lo_at = lo_sample;
    if (std::isfinite(hi_value) && !(hi_value <= hi)) hi = hi_value, hi_at = hi_sample;
  }
  void append_to(std::vector<double>& out) const {  // the two in the order they occur
    out.push_back(lo_at <= hi_at ? lo : hi);
    out.push_back(lo_at <= hi_at ? hi : lo);
  }
};

}  // namespace

void TraceHistory::clear() {
  for (auto* v : {&t_s, &base, &mass, &force_n, &b_m, &z_m, &z_dot_m_s, &restoring_force_n}) {
    v->clear();
  }
}

HistoryRing::HistoryRing(std::uint64_t capacity_samples, double sample_rate_hz)
    : capacity_(std::max<std::uint64_t>(1, (capacity_samples + kChunk - 1) / kChunk) * kChunk),
      chunks_(static_cast<std::size_t>(capacity_ / kChunk)),
      rate_hz_(sample_rate_hz) {
  for (int k = 0; k < kTraces; ++k) {
    traces_[k].assign(static_cast<std::size_t>(capacity_), kNaN);
    summaries_[k].assign(chunks_, Summary{kNaN, kNaN, 0, 0});
  }
  chunk_first_.assign(chunks_, kNoChunk);
}

std::uint64_t HistoryRing::end() const {
  const std::lock_guard lock(mutex_);
  return end_;
}

std::uint64_t HistoryRing::oldest() const {
  if (end_ <= capacity_) return 0;
  // The chunk the oldest kept sample is in may already hold newer samples in its slot.
  return (end_ - capacity_ + kChunk - 1) / kChunk * kChunk;
}

void HistoryRing::start_chunk(std::uint64_t sample) {
  const std::size_t c = chunk(sample);
  const std::uint64_t first = sample / kChunk * kChunk;
  if (chunk_first_[c] == first) return;
  chunk_first_[c] = first;
  for (int k = 0; k < kTraces; ++k) summaries_[k][c] = Summary{kNaN, kNaN, first, first};
}

void HistoryRing::put(int trace, std::uint64_t sample, double value) {
  traces_[trace][slot(sample)] = value;
  if (!std::isfinite(value)) return;
  Summary& s = summaries_[trace][chunk(sample)];
  if (!(value >= s.lo)) s.lo = value, s.lo_at = sample;
  if (!(value <= s.hi)) s.hi = value, s.hi_at = sample;
}

void HistoryRing::write(const BlockWrite& block) {
  const std::lock_guard lock(mutex_);
  const double* measured[3] = {block.base, block.mass, block.force_n};
  for (int r = 0; r < block.measured_count; ++r) {
    const std::uint64_t sample = block.measured_first + static_cast<std::uint64_t>(r);
    start_chunk(sample);
    for (int k = 0; k < 3; ++k) put(k, sample, measured[k] ? measured[k][r] : kNaN);
    for (int k = 3; k < kTraces; ++k) traces_[k][slot(sample)] = kNaN;  // derived later
  }
  if (block.measured_count > 0) {
    end_ = std::max(end_, block.measured_first + static_cast<std::uint64_t>(block.measured_count));
  }
  const double* derived[4] = {block.b_m, block.z_m, block.z_dot_m_s, block.restoring_force_n};
  for (int r = 0; r < block.derived_count; ++r) {
    const std::uint64_t sample = block.derived_first + static_cast<std::uint64_t>(r);
    // Only into a chunk that still holds this sample (not one a newer chunk took over).
    if (sample >= end_ || chunk_first_[chunk(sample)] != sample / kChunk * kChunk) continue;
    for (int k = 0; k < 4; ++k) put(3 + k, sample, derived[k] ? derived[k][r] : kNaN);
  }
}

void HistoryRing::write_gap(std::uint64_t first, std::uint64_t count) {
  const std::lock_guard lock(mutex_);
  const std::uint64_t last = first + count;
  // Only the newest capacity_ samples of a long gap can be in the ring.
  for (std::uint64_t s = last > capacity_ ? std::max(first, last - capacity_) : first; s < last;
       ++s) {
    start_chunk(s);
    for (int k = 0; k < kTraces; ++k) traces_[k][slot(s)] = kNaN;
  }
  end_ = std::max(end_, last);
}

void HistoryRing::read(double from_s, double to_s, int buckets, TraceHistory& out) const {
  out.clear();
  const std::lock_guard lock(mutex_);
  if (end_ == 0 || !(rate_hz_ > 0) || buckets < 1 || !(to_s > from_s)) return;
  const std::uint64_t oldest_kept = oldest();
  const auto clamp_sample = [&](double t) {
    const double s = std::floor(t * rate_hz_);
    if (s <= static_cast<double>(oldest_kept)) return oldest_kept;
    if (s >= static_cast<double>(end_)) return end_;
    return static_cast<std::uint64_t>(s);
  };
  const std::uint64_t first = clamp_sample(from_s), last = clamp_sample(to_s);
  if (last <= first) return;
  const std::uint64_t span = last - first;
  std::uint64_t per_bucket = std::max<std::uint64_t>(1, (span + buckets - 1) / buckets);
  std::vector<double>* targets[kTraces] = {
      &out.base, &out.mass,      &out.force_n,          &out.b_m,
      &out.z_m,  &out.z_dot_m_s, &out.restoring_force_n};
  if (per_bucket == 1) {  // every sample
    for (std::uint64_t s = first; s < last; ++s) {
      out.t_s.push_back(static_cast<double>(s) / rate_hz_);
      for (int k = 0; k < kTraces; ++k) targets[k]->push_back(traces_[k][slot(s)]);
    }
    return;
  }
  const bool from_chunks = per_bucket >= kChunk;
  std::uint64_t start = first;
  if (from_chunks) {  // buckets of whole chunks, aligned to them
    per_bucket = (per_bucket + kChunk - 1) / kChunk * kChunk;
    start = std::max(oldest_kept, first / kChunk * kChunk);
  }
  for (; start < last; start += per_bucket) {
    const std::uint64_t stop = std::min(last, start + per_bucket);
    out.t_s.push_back(static_cast<double>(start) / rate_hz_);
    out.t_s.push_back(static_cast<double>(stop - 1) / rate_hz_);
    for (int k = 0; k < kTraces; ++k) {
      Envelope e;
      e.lo_at = e.hi_at = start;
      if (from_chunks) {
        // Whole chunks, then the samples of a last part-chunk the window ends in.
        std::uint64_t s = start;
        for (; s + kChunk <= stop || (s < stop && stop == end_); s += kChunk) {
          const Summary& c = summaries_[k][chunk(s)];
          e.add(c.lo, c.lo_at, c.hi, c.hi_at);
        }
        for (; s < stop; ++s) {
          const double v = traces_[k][slot(s)];
          e.add(v, s, v, s);
        }
      } else {
        for (std::uint64_t s = start; s < stop; ++s) {
          const double v = traces_[k][slot(s)];
          e.add(v, s, v, s);
        }
      }
      e.append_to(*targets[k]);
    }
  }
}

}  // namespace oscilab::daq
