#include "analysis/hbm/fourier_grid.h"

#include <mutex>
#include <string>

#include <fftw3.h>

#include "analysis/common/input_error.h"
#include "analysis/signal/fftw_planner.h"

namespace oscilab::analysis {
int next_power_of_two(int n) {
  int p = 1;
  while (p < n) p *= 2;
  return p;
}

FourierGrid::FourierGrid(int harmonics, int samples) : harmonics_(harmonics), samples_(samples) {
  if (harmonics < 0 || samples < 1 || 2 * harmonics >= samples) {
    throw InputError("harmonic balance: " + std::to_string(samples) +
                     " time samples cannot carry " + std::to_string(harmonics) +
                     " harmonics (need N > 2H)");
  }
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  real_ = fftw_alloc_real(static_cast<std::size_t>(samples));
  auto* spectrum = fftw_alloc_complex(static_cast<std::size_t>(samples / 2 + 1));
  complex_ = spectrum;
  forward_ = fftw_plan_dft_r2c_1d(samples, real_, spectrum, FFTW_ESTIMATE);
  backward_ = fftw_plan_dft_c2r_1d(samples, spectrum, real_, FFTW_ESTIMATE);
}

FourierGrid::~FourierGrid() {
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  fftw_destroy_plan(static_cast<fftw_plan>(forward_));
  fftw_destroy_plan(static_cast<fftw_plan>(backward_));
  fftw_free(complex_);
  fftw_free(real_);
}

void FourierGrid::synthesise(const Eigen::VectorXd& coefficients, Eigen::VectorXd& value,
                             Eigen::VectorXd& tau_derivative) {
  auto* spectrum = static_cast<fftw_complex*>(complex_);
  const int bins = samples_ / 2 + 1;
  value.resize(samples_);
  tau_derivative.resize(samples_);
  // c2r computes x_n = Σ_k X_k e^{+2πikn/N} over the Hermitian-completed spectrum, so a term
  // Re(X_h e^{ihτ}) needs X_h / 2 in bin h (its conjugate fills bin N − h).
  for (int k = 0; k < bins; ++k) spectrum[k][0] = spectrum[k][1] = 0.0;
  spectrum[0][0] = coefficients[0];
  for (int h = 1; h <= harmonics_; ++h) {
    spectrum[h][0] = 0.5 * coefficients[2 * h - 1];  // a_h / 2
    spectrum[h][1] = -0.5 * coefficients[2 * h];     // −b_h / 2
  }
  fftw_execute(static_cast<fftw_plan>(backward_));
  for (int n = 0; n < samples_; ++n) value[n] = real_[n];

  // d/dτ Re(X_h e^{ihτ}) = Re(i h X_h e^{ihτ}).
  for (int k = 0; k < bins; ++k) spectrum[k][0] = spectrum[k][1] = 0.0;
  for (int h = 1; h <= harmonics_; ++h) {
    const double re = 0.5 * coefficients[2 * h - 1], im = -0.5 * coefficients[2 * h];
    spectrum[h][0] = -h * im;
    spectrum[h][1] = h * re;
  }
  fftw_execute(static_cast<fftw_plan>(backward_));
  for (int n = 0; n < samples_; ++n) tau_derivative[n] = real_[n];
}

void FourierGrid::analyse(const Eigen::VectorXd& value, Eigen::VectorXd& coefficients) {
  auto* spectrum = static_cast<fftw_complex*>(complex_);
  for (int n = 0; n < samples_; ++n) real_[n] = value[n];
  fftw_execute(static_cast<fftw_plan>(forward_));
  const double scale = 1.0 / samples_;
  coefficients.resize(coefficient_count());
  coefficients[0] = spectrum[0][0] * scale;
  for (int h = 1; h <= harmonics_; ++h) {
    coefficients[2 * h - 1] = 2.0 * scale * spectrum[h][0];  // a_h = Re(2 X_h / N)
    coefficients[2 * h] = -2.0 * scale * spectrum[h][1];     // b_h = −Im(2 X_h / N)
  }
}

void FourierGrid::spectrum(const Eigen::VectorXd& value, std::vector<std::complex<double>>& out) {
  auto* spectrum = static_cast<fftw_complex*>(complex_);
  for (int n = 0; n < samples_; ++n) real_[n] = value[n];
  fftw_execute(static_cast<fftw_plan>(forward_));
  const int bins = samples_ / 2 + 1;
  out.resize(static_cast<std::size_t>(bins));
  const double scale = 1.0 / samples_;
  for (int k = 0; k < bins; ++k) out[k] = {spectrum[k][0] * scale, spectrum[k][1] * scale};
}

}  // namespace oscilab::analysis
