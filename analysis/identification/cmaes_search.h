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
/// per thread up to `threads` (pagmo's CMA-ES evaluates its population serially, so the
/// parallelism is across restart sequences). The stream count is fixed, not the machine's core
/// count: a search is the same on a laptop, a cluster node and with `threads` 1. A sequence
/// restarts when its population has collapsed (spread in the cube below `restart_xtol`, or flat
/// costs) or has not improved its best by `restart_ftol_rel` for `stall_generations`. Each sequence
/// is seeded from `seed` and its index, so the result is reproducible for a given seed and stream
/// count, whatever the threads.
struct CmaesOptions {
  long max_evaluations = 1500;
  int streams = 2;             // independent restart sequences
  int threads = 0;             // threads running them; 0: all hardware threads
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
