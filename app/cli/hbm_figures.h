#pragma once

#include <string>
#include <vector>

#include "analysis/hbm/branch.h"
#include "analysis/simulation/amplitude_sweep.h"
#include "analysis/simulation/bifurcation_map.h"
#include "ui/figure.h"

namespace oscilab::cli {

/// A branch with the name it has in a figure's legend.
struct NamedBranch {
  std::string name;  // e.g. "z+* well"
  const analysis::Branch* branch = nullptr;
};

/// Figs. 11 and 15: amplitude and EDC against f0 (stable parts solid, unstable dashed, folds and
/// period doublings marked); with one branch also its harmonics |Z_h| / |Z_1|.
ui::Figure branch_figure(const std::string& title, const std::vector<NamedBranch>& branches);

/// Fig. 12: the time-integration sweep up and down over the HBM amplitude.
ui::Figure sweep_figure(const std::string& title, const analysis::Branch& branch,
                        const analysis::AmplitudeSweep& sweep);

/// Fig. 17: the Poincaré sections of the map over the HBM orbit's z at the same phase (t = nT),
/// and the HBM amplitude below.
ui::Figure map_figure(const std::string& title, const std::vector<NamedBranch>& branches,
                      const analysis::BifurcationMap& map);

}  // namespace oscilab::cli
