#pragma once

#include <Eigen/Core>

namespace oscilab::analysis {

/// The dominant sinusoid of a record: its frequency and how much of the signal's power it holds.
struct DominantTone {
  double freq_hz = 0.0;
  double power_fraction = 0.0;  // power within ±4 bins of the peak / total AC power, in [0, 1]
};

/// Finds the dominant tone by the FFT of the Hann-windowed, mean-removed record and Gaussian
/// interpolation of the three bins around the peak (Gasior & Gonzalez 2004, "Improving FFT
/// frequency measurement resolution by parabolic and Gaussian spectrum interpolation"), then
/// refined by a golden-section search for the maximum of the unwindowed record's DTFT magnitude
/// within ±1 bin, which is unbiased for a sine under a non-negative amplitude envelope (stepped
/// levels). Bins below `min_hz` are ignored (sensor drift).
DominantTone dominant_tone(const Eigen::VectorXd& x, double sample_rate_hz, double min_hz = 0.5);

}  // namespace oscilab::analysis
