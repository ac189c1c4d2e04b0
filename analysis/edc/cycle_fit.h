#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

#include "analysis/signal/motion_quantity.h"

namespace oscilab::analysis {

/// One forcing cycle, analysed by least-squares harmonic fits (§4.1, eqs. (11)–(13)).
///
/// Over the window [start, start + T), T = 1/ν, the base and mass signals are each fitted by
///   x(t) ≈ a + c·(t − t_mid) + Re Σ_{h=1..H} X_h e^{ihω(t − t_ref)},
/// with t_ref a fixed reference time (so harmonics of consecutive cycles are comparable). The
/// linear term absorbs sensor drift and table creep within the cycle. Each channel's harmonics
/// are converted to displacement by X_h / (ihω)^order, so that
///   B_h (table), Y_h (mass), Z_h = Y_h − B_h, F_h = m (hω)² B_h  (f = −m b̈, eq. (1)).
/// The energy dissipated in the cycle is then exact for a band-limited periodic motion:
///   S = ∮ f dz = ∫ f ż dt = (T/2) Σ_h hω Im(F_h · conj(Z_h))                        (Parseval)
/// and the paper's first-harmonic estimate is eq. (13), S₁ = π f0 |Z1| sin θ1, θ1 the lag of z
/// behind f (docs/conventions.md). Both are positive for a lossy system.
struct CycleFit {
  double start_s = 0.0;
  double end_s = 0.0;
  double f0_n = 0.0;      // |F1|: amplitude of the force's first harmonic
  double z_mean_m = 0.0;  // mean of z over the cycle (from the fit's constant terms)
  double z_min_m = 0.0;   // extremes of the fitted z over the cycle
  double z_max_m = 0.0;
  std::vector<std::complex<double>> z_h;  // Z_1..Z_H, displacement [m], phase at t_ref
  double y1_abs_m = 0.0;     // |Y1|: the mass channel's first harmonic as displacement (|Z1| when
                             // the channel measures z)
  double lag_rad = 0.0;      // θ1 ∈ (−π, π]
  double edc_j = 0.0;        // ∮ f dz from all fitted harmonics
  double edc_eq13_j = 0.0;   // π f0 |Z1| sin θ1
  double edc_trapz_j = 0.0;  // trapezoidal ∮ f dz on the samples (f measured, z = y − b_fit)
  double base_residual_rms = 0.0;  // fit residuals, in the channel's own SI unit
  double mass_residual_rms = 0.0;
  int samples = 0;
};

struct CycleFitInput {
  double freq_hz = 0.0;
  double mass_kg = 1.0;
  int harmonics = 8;
  double t_ref_s = 0.0;
  MotionQuantity base_quantity = MotionQuantity::Acceleration;
  MotionQuantity mass_quantity = MotionQuantity::Displacement;
  bool mass_is_relative = false;  // the mass channel measures z directly (role "relative")
  int min_samples = 0;  // fewer samples inside the window (a gap): the cycle is not fitted
};

/// Fits one cycle. `t_s`, `base`, `mass` hold the samples inside [start_s, start_s + 1/ν) plus
/// one sample on each side (for the trapezoid's partial intervals at the window edges), sorted
/// by time. Returns false when the window holds fewer than `min_samples` samples or too few for
/// even one harmonic (H is lowered to (n − 3)/2 when the window holds n < 2H + 3 samples).
bool fit_cycle(const CycleFitInput& input, double start_s, const double* t_s, const double* base,
               const double* mass, int count, CycleFit& out);

}  // namespace oscilab::analysis
