#pragma once

#include <complex>

#include <fftw3.h>

namespace oscilab::analysis {

/// The DFT of a real record of length n, in FFTW's r2c/c2r conventions (unnormalised):
///   forward:  X_k = Σ_j x_j e^{−2πijk/n}, k = 0..n/2 (the n/2 + 1 non-redundant bins);
///   inverse:  x_j · n = Σ_k X_k e^{+2πijk/n} over the Hermitian spectrum, from the n/2 + 1 bins
///             (the imaginary parts of X_0 and, for even n, of X_{n/2} are ignored).
///
/// For even n it runs one complex DFT of length m = n/2 (FFTW) on the record read as m complex
/// samples z_j = x_{2j} + i x_{2j+1}, and one pass that splits Z into the spectra of the even and
/// odd samples and joins them with the twiddles W^k = e^{−2πik/n}:
///   E_k = (Z_k + conj Z_{m−k}) / 2,  O_k = (Z_k − conj Z_{m−k}) / 2i,  X_k = E_k + W^k O_k,
/// and the same steps backwards for the inverse (the classic real-FFT by a half-length complex
/// FFT). The reason is the cost of planning in a fresh process, where each record length is met
/// once: FFTW_ESTIMATE searches its real-data solvers for the r2c and c2r plans, which at the
/// length of a 262.5 s stepped-sine record's even extension at 512 Hz (268 800 points) costs
/// several times the complex plan of half that length, while the transforms themselves cost
/// about the same (analysis_benchmark: BM_RealFftFirstUse against BM_FftwRealPlansFirstUse).
/// Odd n uses FFTW's r2c and c2r plans directly.
///
/// Arrays must be aligned as fftw_malloc aligns them (FftwVector), like the plans they run.
/// Thread-safe: one object serves every thread (FFTW's new-array execute functions are).
class RealFft {
 public:
  /// The transform of length n (≥ 2), made on first use and kept for the process's life.
  static const RealFft& of_size(int n);

  explicit RealFft(int n);  // makes the plans: hold fftw_planner_mutex()
  ~RealFft();               // destroys them: hold fftw_planner_mutex()
  RealFft(const RealFft&) = delete;
  RealFft& operator=(const RealFft&) = delete;

  int size() const { return n_; }
  int bins() const { return n_ / 2 + 1; }

  /// x: n values (read only); spectrum: bins() values.
  void forward(const double* x, std::complex<double>* spectrum) const;
  /// spectrum: bins() values, used as scratch and left undefined (as FFTW's c2r does); x: n.
  void inverse(std::complex<double>* spectrum, double* x) const;

 private:
  int n_ = 0;
  fftw_plan forward_ = nullptr;               // even n: complex, length n/2; odd n: r2c
  fftw_plan inverse_ = nullptr;               // even n: complex backward, length n/2; odd n: c2r
  std::complex<double>* twiddles_ = nullptr;  // W^k for k = 0..n/4 (even n)
};

}  // namespace oscilab::analysis
