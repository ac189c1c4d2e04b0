#include "analysis/signal/fftw_planner.h"

#include <map>
#include <utility>

namespace oscilab::analysis {
namespace {

// Plans by (size, direction), kept until the process exits (a process meets only a handful of
// sizes), then destroyed so that nothing FFTW allocated outlives the program.
struct PlanCache {
  std::map<std::pair<int, bool>, fftw_plan> plans;
  PlanCache() = default;
  PlanCache(const PlanCache&) = delete;
  PlanCache& operator=(const PlanCache&) = delete;
  ~PlanCache() {
    const std::lock_guard lock(fftw_planner_mutex());
    for (auto& [key, plan] : plans) fftw_destroy_plan(plan);
  }
};

fftw_plan cached_plan(int n, bool forward) {
  // The mutex is made first, so it outlives the cache when statics are destroyed.
  std::mutex& mutex = fftw_planner_mutex();
  static PlanCache cache;
  const std::lock_guard lock(mutex);
  auto& plans = cache.plans;
  const auto key = std::make_pair(n, forward);
  if (const auto it = plans.find(key); it != plans.end()) return it->second;
  double* real = fftw_alloc_real(static_cast<std::size_t>(n));
  fftw_complex* spectrum = fftw_alloc_complex(static_cast<std::size_t>(n / 2 + 1));
  const unsigned flags = FFTW_ESTIMATE;
  const fftw_plan plan = forward ? fftw_plan_dft_r2c_1d(n, real, spectrum, flags)
                                 : fftw_plan_dft_c2r_1d(n, spectrum, real, flags);
  fftw_free(real);
  fftw_free(spectrum);
  plans.emplace(key, plan);
  return plan;
}

}  // namespace

std::mutex& fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

fftw_plan cached_r2c_plan(int n) { return cached_plan(n, true); }
fftw_plan cached_c2r_plan(int n) { return cached_plan(n, false); }

}  // namespace oscilab::analysis
