#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace oscilab::analysis {

/// A real periodic signal on N equally spaced samples of one period, τ_n = 2π n / N, and its
/// truncated real Fourier series (docs/conventions.md, "Fourier transforms"):
///
///   x(τ) = a0 + Σ_{h=1..H} a_h cos(hτ) + b_h sin(hτ)  =  a0 + Σ Re(X_h e^{ihτ}),  X_h = a_h − i
///   b_h
///
/// Coefficients are stored as the real vector [a0, a1, b1, …, aH, bH] (size 2H + 1), the unknowns
/// of harmonic balance. Transforms are FFTW real-to-complex / complex-to-real plans made once;
/// FFTW is unnormalised, and the 1/N sits in `analyse` only (backward(forward(x)) = N x).
///
/// Thread-safety: plan creation is serialised internally (FFTW's planner is not thread-safe);
/// one grid must not be used from two threads at once (it owns its work buffers).
class FourierGrid {
 public:
  /// Throws InputError unless 0 ≤ H and 2H < N (the Nyquist bin is never a harmonic).
  FourierGrid(int harmonics, int samples);
  ~FourierGrid();
  FourierGrid(const FourierGrid&) = delete;
  FourierGrid& operator=(const FourierGrid&) = delete;

  int harmonics() const { return harmonics_; }
  int samples() const { return samples_; }
  int coefficient_count() const { return 2 * harmonics_ + 1; }

  /// x(τ_n) and dx/dτ(τ_n) from the coefficients (two backward transforms).
  void synthesise(const Eigen::VectorXd& coefficients, Eigen::VectorXd& value,
                  Eigen::VectorXd& tau_derivative);
  /// Coefficients [a0, a1, b1, …] of the samples up to harmonic H: the discrete projections
  /// a0 = (1/N) Σ x_n, a_h = (2/N) Σ x_n cos hτ_n, b_h = (2/N) Σ x_n sin hτ_n (aliasing included).
  void analyse(const Eigen::VectorXd& value, Eigen::VectorXd& coefficients);
  /// The normalised DFT w_m = (1/N) Σ x_n e^{−i m τ_n} for m = 0 … N/2 (the rest follows from
  /// w_{−m} = conj(w_m) and w_{m+N} = w_m).
  void spectrum(const Eigen::VectorXd& value, std::vector<std::complex<double>>& out);

 private:
  int harmonics_;
  int samples_;
  double* real_ = nullptr;
  void* complex_ = nullptr;   // fftw_complex[N/2 + 1]
  void* forward_ = nullptr;   // fftw_plan r2c
  void* backward_ = nullptr;  // fftw_plan c2r
};

/// Smallest power of two ≥ n (n ≥ 1).
int next_power_of_two(int n);

}  // namespace oscilab::analysis
