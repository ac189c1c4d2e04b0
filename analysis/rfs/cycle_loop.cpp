#include "analysis/rfs/cycle_loop.h"

#include <cassert>
#include <cmath>
#include <cstddef>

namespace oscilab::analysis {

CycleLoop newest_cycle_loop(const std::vector<double>& t_s, const std::vector<double>& z_m,
                            const std::vector<double>& f_n, double frequency_hz,
                            double well_boundary_m) {
  assert(z_m.size() == t_s.size() && f_n.size() == t_s.size());
  CycleLoop loop;
  if (!(frequency_hz > 0) || t_s.size() < 2) return loop;
  const auto finite = [&](std::size_t i) { return std::isfinite(z_m[i]) && std::isfinite(f_n[i]); };
  std::size_t last = t_s.size();
  while (last > 0 && !finite(last - 1)) --last;
  if (last < 2) return loop;
  const double end_s = t_s[last - 1];
  const double dt = t_s[1] - t_s[0];
  const double start_s = end_s - 1.0 / frequency_hz;  // one whole period, closed
  std::size_t first = last - 1;
  while (first > 0 && finite(first - 1) && t_s[first - 1] > start_s - 0.5 * dt) --first;
  if (t_s[first] > start_s + 0.5 * dt) return loop;  // less than a cycle
  double sum = 0.0;
  for (std::size_t i = first; i < last; ++i) {
    loop.z_m.push_back(z_m[i]);
    loop.f_n.push_back(f_n[i]);
    sum += z_m[i];
  }
  loop.start_s = t_s[first];
  loop.end_s = end_s;
  loop.positive = sum / static_cast<double>(loop.z_m.size()) > well_boundary_m;
  return loop;
}

}  // namespace oscilab::analysis
