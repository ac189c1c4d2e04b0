#pragma once

#include <vector>

namespace oscilab::analysis {

/// Live integration (or differentiation) of a sampled signal with a fixed, bounded latency.
///
/// The offline integrator (spectral_derivative) is zero-phase and so needs the whole record. Live
/// work cannot look ahead, but it can wait: this is the same zero-phase frequency response
/// W(f)·(i2πf)^order (the same band window, SpectralOptions), as a linear-phase FIR filter of
/// 2K + 1 taps delayed by K samples. Each output is the offline result at t − latency, with no
/// phase error at any frequency; the only difference from offline is the truncation of the
/// impulse response to ±K samples (Tukey-tapered over its outer half), which the caller trades
/// against latency. With the default 1 Hz high-pass and a 4 s latency, a 9 Hz sine double
/// integrates to within 1e-4 of its amplitude (tests/analysis/signal).
///
/// The filter taps are designed once (FFTW, in the constructor); push() costs 2K + 1
/// multiply-adds and never allocates. Not thread-safe: one producer thread.
class StreamingIntegrator {
 public:
  struct Options {
    double sample_rate_hz = 512.0;
    int order = -2;            // −2: double integral; −1, 0, 1, 2 likewise
    double highpass_hz = 1.0;  // as SpectralOptions (used when integrating)
    double lowpass_hz = 0.0;   // as SpectralOptions (0: none)
    double latency_s = 4.0;    // K / sample rate
  };
  explicit StreamingIntegrator(const Options& options);  // throws InputError on bad options

  /// Feeds one sample; returns the filtered value for the sample `latency_samples()` ago (0 until
  /// the filter is full: ready() tells).
  double push(double x);
  bool ready() const { return pushed_ >= static_cast<long>(taps_.size()); }
  int latency_samples() const { return half_width_; }
  double latency_s() const { return half_width_ / sample_rate_hz_; }
  const std::vector<double>& taps() const { return taps_; }

 private:
  double sample_rate_hz_;
  int half_width_;
  std::vector<double> taps_;     // h[−K..K], already including the 1/fs of the integral
  std::vector<double> history_;  // ring buffer of the last 2K + 1 inputs, twice for contiguity
  std::size_t head_ = 0;
  long pushed_ = 0;
};

}  // namespace oscilab::analysis
