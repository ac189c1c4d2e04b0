#pragma once

#include <cstdint>

#include "analysis/common/job.h"
#include "analysis/identification/unit_search.h"

namespace oscilab::analysis {

/// The paper's genetic algorithm (§4, §5: population 100, 20 generations, 20 % mutation), a
/// real-coded GA over the unit cube in the manner of MATLAB's `ga`, which the paper's settings
/// name:
///
///  - generation 0: `population` points drawn uniformly;
///  - each generation keeps the `elite` best unchanged; of the other children, a fraction
///    `crossover_fraction` come from scattered crossover of two parents (each gene from either
///    with probability ½), the rest are copies of one parent; parents are chosen by binary
///    tournament;
///  - every gene of a non-elite child mutates with probability `mutation_rate` by a Gaussian
///    step whose σ shrinks linearly from `mutation_sigma` (generation 1) to a tenth of it (last
///    generation), clipped to the cube.
///
/// Evaluations: population + generations × (population − elite); 2000 for the paper's settings
/// with the default 5 % elite. A generation's children are evaluated in parallel on `threads`
/// threads; all random draws happen on the calling thread, so the same seed gives the same
/// result and evaluation count for any thread count.
struct GeneticOptions {
  int population = 100;
  int generations = 20;
  double mutation_rate = 0.2;
  double crossover_fraction = 0.8;
  int elite = 5;
  double mutation_sigma = 0.1;  // in unit-cube lengths
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all hardware threads
};

/// Throws InputError for settings outside their ranges (population < 2, elite ≥ population,
/// rates outside [0, 1]).
SearchResult genetic_algorithm(int dimension, const UnitCost& cost, const GeneticOptions& options,
                               const SearchProgressFn& progress = {},
                               const CancelToken& cancel = {});

}  // namespace oscilab::analysis
