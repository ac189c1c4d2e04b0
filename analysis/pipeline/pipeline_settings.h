#pragma once

#include <nlohmann/json.hpp>

namespace oscilab::analysis {

/// Every setting of the measurement analysis, identical live and offline and stored in each
/// result (to_json), so a number can always be traced to how it was made.
struct PipelineSettings {
  int harmonics = 8;                     // per-cycle harmonic fit order H (lowered at low rates)
  double well_boundary_m = 0.0;          // z between the wells (§2: rods horizontal at z = 0)
  int min_steady_cycles = 5;             // fewer steady cycles: the level is flagged few-cycles
  double steady_rel_tol = 2e-4;          // steady-state band, relative part
  double level_change_rel = 0.03;        // level detection without sidecar levels
  double integration_highpass_hz = 1.0;  // zero-phase double integration of b̈: cut-off
  double derivative_lowpass_hz = 60.0;   // spectral differentiation of y: cut-off
  double stiffness_velocity_band_rel = 0.02;  // stiffness slice: |ż| < this × p99(|ż|)
  int stiffness_bins = 60;
  double damping_position_band_rel = 0.01;  // damping slice: |z − z̄| < this × z range
  int damping_bins = 40;
  double edge_trim_s = 1.0;  // samples this close to a record's ends are left out of RFS

  nlohmann::json to_json() const;
  /// Throws InputError naming the first setting out of its range and its value, e.g.
  /// "analysis setting harmonics = 0: at least 1 harmonic per cycle fit". The analysis (offline
  /// and live) checks its settings before it starts, whichever front end set them.
  void validate() const;
};

}  // namespace oscilab::analysis
