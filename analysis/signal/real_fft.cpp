#include "analysis/signal/real_fft.h"

#include <cmath>
#include <map>
#include <memory>
#include <numbers>

#include "analysis/common/input_error.h"
#include "analysis/signal/fftw_planner.h"

namespace oscilab::analysis {
namespace {

fftw_complex* as_fftw(std::complex<double>* x) { return reinterpret_cast<fftw_complex*>(x); }

// Transforms by size, kept until the process exits (a process meets only a handful of sizes),
// then destroyed so that nothing FFTW allocated outlives the program.
struct RealFftCache {
  std::map<int, std::unique_ptr<RealFft>> transforms;
  RealFftCache() = default;
  RealFftCache(const RealFftCache&) = delete;
  RealFftCache& operator=(const RealFftCache&) = delete;
  ~RealFftCache() {
    const std::lock_guard lock(fftw_planner_mutex());
    transforms.clear();
  }
};

}  // namespace

const RealFft& RealFft::of_size(int n) {
  // The mutex is made first, so it outlives the cache when statics are destroyed.
  std::mutex& mutex = fftw_planner_mutex();
  static RealFftCache cache;
  const std::lock_guard lock(mutex);
  std::unique_ptr<RealFft>& transform = cache.transforms[n];
  if (!transform) transform = std::make_unique<RealFft>(n);
  return *transform;
}

RealFft::RealFft(int n) : n_(n) {
  if (n < 2) throw InputError("real FFT: length " + std::to_string(n) + " below 2");
  const unsigned flags = FFTW_ESTIMATE;
  if (n % 2 == 1) {
    double* real = fftw_alloc_real(static_cast<std::size_t>(n));
    fftw_complex* spectrum = fftw_alloc_complex(static_cast<std::size_t>(bins()));
    forward_ = fftw_plan_dft_r2c_1d(n, real, spectrum, flags);
    inverse_ = fftw_plan_dft_c2r_1d(n, spectrum, real, flags);
    fftw_free(real);
    fftw_free(spectrum);
    return;
  }
  const int m = n / 2;
  fftw_complex* a = fftw_alloc_complex(static_cast<std::size_t>(m));
  fftw_complex* b = fftw_alloc_complex(static_cast<std::size_t>(m));
  forward_ = fftw_plan_dft_1d(m, a, b, FFTW_FORWARD, flags);
  inverse_ = fftw_plan_dft_1d(m, a, b, FFTW_BACKWARD, flags);
  fftw_free(a);
  fftw_free(b);
  // W^k = e^{−2πik/n} for k ≤ n/4, the pairs (k, m − k) need no more. Directly for k ≤ n/8;
  // beyond, by W^{n/4 − k} = −i conj(W^k) when n/4 is whole (exact, and half the sincos calls).
  const int quarter = m / 2;
  twiddles_ = reinterpret_cast<std::complex<double>*>(
      fftw_alloc_complex(static_cast<std::size_t>(quarter + 1)));
  const bool reflect = m % 2 == 0;
  const int direct = reflect ? quarter / 2 : quarter;
  for (int k = 0; k <= direct; ++k) {
    twiddles_[k] = std::polar(1.0, -2.0 * std::numbers::pi * k / n);
  }
  for (int k = direct + 1; k <= quarter; ++k) {
    twiddles_[k] = std::complex<double>(0.0, -1.0) * std::conj(twiddles_[quarter - k]);
  }
}

RealFft::~RealFft() {
  if (forward_ != nullptr) fftw_destroy_plan(forward_);
  if (inverse_ != nullptr) fftw_destroy_plan(inverse_);
  fftw_free(twiddles_);
}

void RealFft::forward(const double* x, std::complex<double>* spectrum) const {
  // Out-of-place transforms other than c2r leave their input as it was (FFTW's default
  // FFTW_PRESERVE_INPUT), so the cast only satisfies the C signature.
  auto* input = const_cast<double*>(x);  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  if (n_ % 2 == 1) {
    fftw_execute_dft_r2c(forward_, input, as_fftw(spectrum));
    return;
  }
  const int m = n_ / 2;
  // Z = DFT_m(x_{2j} + i x_{2j+1}), into the first m bins, then split pairwise in place.
  fftw_execute_dft(forward_, reinterpret_cast<fftw_complex*>(input), as_fftw(spectrum));
  const std::complex<double> z0 = spectrum[0];
  spectrum[0] = z0.real() + z0.imag();
  spectrum[m] = z0.real() - z0.imag();
  const std::complex<double> half_over_i(0.0, -0.5);  // 1 / 2i
  for (int k = 1; 2 * k <= m; ++k) {
    const std::complex<double> zk = spectrum[k], zmk = spectrum[m - k];
    const std::complex<double> even = 0.5 * (zk + std::conj(zmk));
    const std::complex<double> odd = half_over_i * (zk - std::conj(zmk));
    const std::complex<double> w_odd = twiddles_[k] * odd;
    spectrum[k] = even + w_odd;
    // E_{m−k} = conj E_k, O_{m−k} = conj O_k and W^{m−k} = −conj W^k.
    spectrum[m - k] = std::conj(even - w_odd);
  }
}

void RealFft::inverse(std::complex<double>* spectrum, double* x) const {
  if (n_ % 2 == 1) {
    fftw_execute_dft_c2r(inverse_, as_fftw(spectrum), x);
    return;
  }
  const int m = n_ / 2;
  // Z_k = 2 E_k + 2i O_k, with E_k = (X_k + conj X_{m−k}) / 2 and
  // O_k = (X_k − conj X_{m−k}) conj(W^k) / 2 (from X_k = E_k + W^k O_k and
  // conj X_{m−k} = E_k − W^k O_k). The unnormalised backward transform of length m returns
  // m (x_{2j} + i x_{2j+1}) from E + iO, so the factor 2 gives n x_j, as c2r does.
  const double x0 = spectrum[0].real(), xm = spectrum[m].real();
  spectrum[0] = std::complex<double>(x0 + xm, x0 - xm);
  const std::complex<double> i(0.0, 1.0);
  for (int k = 1; 2 * k <= m; ++k) {
    const std::complex<double> xk = spectrum[k], xmk = spectrum[m - k];
    const std::complex<double> w = twiddles_[k];
    spectrum[k] = (xk + std::conj(xmk)) + i * (xk - std::conj(xmk)) * std::conj(w);
    // The pair's own formula at m − k, with conj(W^{m−k}) = −W^k.
    spectrum[m - k] = (xmk + std::conj(xk)) - i * (xmk - std::conj(xk)) * w;
  }
  fftw_execute_dft(inverse_, as_fftw(spectrum), reinterpret_cast<fftw_complex*>(x));
}

}  // namespace oscilab::analysis
