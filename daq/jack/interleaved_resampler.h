#pragma once

#include <cstddef>
#include <string>
#include <vector>

struct soxr;  // libsoxr's resampler (soxr.h), kept out of this header

namespace oscilab::daq {

/// Every channel of a sound card resampled together by one libsoxr instance, interleaved, so
/// that every channel passes the same filter with the same delay (the base–mass phase the EDC
/// rests on is untouched):
///   - anti-alias filter: SOXR_HQ (20-bit precision, ≥ 120 dB stopband rejection), linear phase,
///     passband flat to passband_end × the output Nyquist, stopband from the output Nyquist up;
///   - soxr removes the filter's group delay itself: output sample k is the input signal at
///     t = k / rate_out exactly. What remains is a latency: ~70 output samples with the DFT
///     sizes used (2^6..2^8) are held back and come out once computed (flush() at the end).
/// Input frames are float (a JACK buffer), output samples double, both interleaved.
///
/// Thread-safety: one thread at a time. process(), flush() and clear() allocate nothing.
class InterleavedResampler {
 public:
  InterleavedResampler() = default;
  ~InterleavedResampler();
  InterleavedResampler(const InterleavedResampler&) = delete;
  InterleavedResampler& operator=(const InterleavedResampler&) = delete;

  /// A resampler from rate_in to rate_out over `channels`, with room to take up to
  /// `max_input_frames` at once; replaces any earlier one. Returns "" or why not.
  std::string open(double rate_in, double rate_out, std::size_t channels, double passband_end,
                   std::size_t max_input_frames);
  bool is_open() const { return resampler_ != nullptr; }
  /// Back to the state of a fresh resampler (no history, no held-back samples).
  void clear();
  /// Feeds up to `frames` frames, interleaved; `used` says how many it took. Returns how many
  /// output samples (per channel) it made into output().
  std::size_t process(const float* frames, std::size_t count, std::size_t& used);
  /// The end of the input: the held-back samples, completed with silence, into output(). Call
  /// until it returns 0.
  std::size_t flush();
  /// The last process() or flush()'s samples, interleaved.
  const double* output() const { return out_.data(); }

  /// How far (output samples) the impulse response of this design reaches on either side, to
  /// 1e-6 of its peak: an impulse through a scratch instance (24 at 48 kHz → 512 Hz).
  static int measure_reach(double rate_in, double rate_out, double passband_end);

 private:
  soxr* resampler_ = nullptr;
  std::size_t channels_ = 0;
  std::vector<double> out_;  // room for one process() call's output, interleaved
};

}  // namespace oscilab::daq
