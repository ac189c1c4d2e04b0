#pragma once

#include <vector>

namespace oscilab::analysis {

/// The force–displacement loop (f against z, Fig. 9) of one whole cycle.
struct CycleLoop {
  std::vector<double> z_m, f_n;
  double start_s = 0.0, end_s = 0.0;
  bool positive = true;  // mean z above the well boundary
};

/// The loop of the newest whole cycle whose z is known: the last 1/ν of the samples (t_s, z_m
/// and f_n of equal length, one per sample period) that have finite z and f. Empty when there
/// is less than a cycle.
CycleLoop newest_cycle_loop(const std::vector<double>& t_s, const std::vector<double>& z_m,
                            const std::vector<double>& f_n, double frequency_hz,
                            double well_boundary_m = 0.0);

}  // namespace oscilab::analysis
