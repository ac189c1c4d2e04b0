#pragma once

#include <cstdint>

#include "analysis/common/job.h"
#include "analysis/identification/unit_search.h"

namespace oscilab::analysis {

/// CMA-ES with restarts over the unit cube (Hansen & Ostermeier 2001, "Completely derandomized
/// self-adaptation in evolution strategies"; restarts with a doubled population, IPOP: Auger &
/// Hansen 2005, "A restart CMA evolution strategy with increasing population size"), on pagmo2's
/// `cmaes`.
///
/// The budget is shared by `streams` independent restart sequences that run in parallel, one
/// per thread (pagmo's CMA-ES evaluates its population serially, so the parallelism is across
/// restart sequences). A sequence restarts when its population has collapsed (spread in the cube
/// below `restart_xtol`, or flat costs) or has not improved its best by `restart_ftol_rel` for
/// `stall_generations`. Each sequence is seeded from `seed` and its index, so the result is
/// reproducible for a given seed and stream count.
struct CmaesOptions {
  long max_evaluations = 1500;
  int streams = 0;             // parallel restart sequences; 0: all hardware threads
  int initial_population = 0;  // λ of the first run; 0: 4 + ⌊3 ln p⌋ (Hansen's default), ≥ 8
  double sigma0 = 0.3;         // initial step in unit-cube lengths
  double restart_xtol = 1e-6;
  double restart_ftol_rel = 1e-9;
  int stall_generations = 25;
  std::uint64_t seed = 1;
};

SearchResult cmaes_search(int dimension, const UnitCost& cost, const CmaesOptions& options,
                          const SearchProgressFn& progress = {}, const CancelToken& cancel = {});

}  // namespace oscilab::analysis
