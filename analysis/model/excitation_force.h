#pragma once

#include <complex>

namespace oscilab::analysis {

/// The excitation of eq. (1): the shaking table's acceleration b̈ drives the mass as the force
/// f = −m b̈ (N; N/kg with a unit mass). One place for the sign and the factor, for a sample, a
/// vector of samples (any type with scalar multiplication) and the simulated table alike.
template <class Acceleration>
Acceleration excitation_force_n(double mass_kg, const Acceleration& base_acceleration_m_s2) {
  return -mass_kg * base_acceleration_m_s2;
}

/// Eq. (1) for the h-th harmonic of a table displacement B_h at angular frequency h ω:
/// F_h = −m (i h ω)² B_h = m (h ω)² B_h.
inline std::complex<double> excitation_force_harmonic(double mass_kg, double h_omega_rad_s,
                                                      std::complex<double> base_displacement_m) {
  return excitation_force_n(mass_kg, -h_omega_rad_s * h_omega_rad_s * base_displacement_m);
}

}  // namespace oscilab::analysis
