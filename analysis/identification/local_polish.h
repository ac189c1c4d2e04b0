#pragma once

#include "analysis/common/job.h"
#include "analysis/identification/unit_search.h"

namespace oscilab::analysis {

/// Local refinement of a search's best point: NLopt's BOBYQA (Powell 2009, "The BOBYQA algorithm
/// for bound constrained optimization without derivatives"), a trust-region method on quadratic
/// models of the cost, inside the unit cube. Derivative-free because the EDC of a friction model
/// is only piecewise smooth in θ (max{0, ·} of eq. (6), branch changes), and each evaluation is
/// a continuation that finite differences would multiply.
struct PolishOptions {
  long max_evaluations = 400;
  double initial_step = 0.02;  // trust-region radius at the start, unit-cube lengths
  double xtol_rel = 1e-7;
  double ftol_rel = 1e-12;
};

SearchResult local_polish(const Eigen::VectorXd& start_unit, const UnitCost& cost,
                          const PolishOptions& options, const SearchProgressFn& progress = {},
                          const CancelToken& cancel = {});

}  // namespace oscilab::analysis
