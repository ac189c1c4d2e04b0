#pragma once

#include <vector>

namespace oscilab::analysis {

/// One-sided amplitude spectrum of z (docs/conventions.md: a sine of amplitude A reads A) with
/// a Hann window, and the amplitudes at the excitation's harmonics h ν, h = 1 … H, each by a
/// direct DFT at exactly h ν (so a harmonic between bins reads its amplitude, not a scalloped
/// one), and at ν/2 (a period-doubling's first sign, Fig. 17).
struct ZSpectrum {
  std::vector<double> freq_hz;
  std::vector<double> amplitude_m;
  std::vector<double> harmonic_freq_hz;
  std::vector<double> harmonic_amplitude_m;
  double subharmonic_amplitude_m = 0.0;  // at ν/2
  double duration_s = 0.0;               // of the stretch analysed
};
/// `z_m` sampled at `sample_rate_hz` (non-finite samples are skipped from the start: the
/// newest finite stretch is used); empty when it holds fewer than 64 samples.
ZSpectrum z_spectrum(const std::vector<double>& z_m, double sample_rate_hz, double frequency_hz,
                     int harmonics = 8);

}  // namespace oscilab::analysis
