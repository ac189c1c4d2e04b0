#pragma once

#include "analysis/model/model.h"

namespace oscilab::analysis {

/// The paper's identified model, eq. (7): Table 1 stiffness (k3 = 7.35e5 N/m³, k2 = 1.56e3 N/m²,
/// k1 = 550 N/m, k0 = 2.4 N), m = 0.26 kg, and Table 3 friction: f_d(z₋*) = 0.33 N,
/// f_d(0) = 0.67 N, f_d(z₊*) = 0.66 N (the parabola of eq. (6) through these three points at the
/// model's own equilibria), k_s = 1.07, c = 2.02 N s/m, v_t = 1.5e-2 m/s.
Model paper_model();

/// The illustrative linear oscillator with friction of eq. (14), Table 2: m = 1.3 kg,
/// k = 800 N/m, c = 1 N s/m, f_d = 1 N, k_s = 1.2, v_t = 1e-2 m/s.
Model illustrative_model();

/// A linear oscillator m z̈ + c ż + k z = f: the closed-form reference of many tests.
Model linear_oscillator_model(double mass_kg, double k_n_m, double c_ns_m);

/// Table 3 values, named as the paper's θ of eq. (9).
struct PaperFriction {
  double fd_zminus_n = 0.33;
  double fd_zero_n = 0.67;
  double fd_zplus_n = 0.66;
  double ks = 1.07;
  double c_ns_m = 2.02;
  double vt_m_s = 1.5e-2;
};

/// The paper's model form with other friction values (the stiffness stays Table 1).
Model paper_model(const PaperFriction& friction);

}  // namespace oscilab::analysis
