#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "analysis/edc/well.h"
#include "analysis/figures/figure.h"
#include "analysis/hbm/branch.h"
#include "analysis/simulation/amplitude_sweep.h"
#include "analysis/simulation/bifurcation_map.h"

namespace oscilab::figures {

/// A branch with the name it has in a figure's legend.
struct NamedBranch {
  std::string name;  // e.g. "z+* well"
  const analysis::Branch* branch = nullptr;
};

/// A branch as a part of a branch CSV: the well it grew from and the period of its orbits in
/// forcing periods (1, 2, 4 …).
struct CsvBranch {
  const analysis::Branch* branch = nullptr;
  analysis::Well well = analysis::Well::Positive;  // Positive or Negative
  int period = 1;
};

/// The branch CSV of docs/contracts.md §3 (analysis::write_branch_csv) of one branch, or of several
/// with a `well` column appended (`well_column`), and with `period` appended after it
/// (`period_column`): the contract's own columns come first and keep their order. Throws InputError
/// naming the file when it cannot be written.
void write_branches_csv(const std::vector<CsvBranch>& branches, bool well_column,
                        bool period_column, const std::string& path);
/// The same into a stream (the caller checks it).
void write_branches_csv(const std::vector<CsvBranch>& branches, bool well_column,
                        bool period_column, std::ostream& out);

/// Figs. 11 and 15: amplitude and EDC against f0 (stable parts solid, unstable dashed, folds and
/// period doublings marked); with one branch also its harmonics |Z_h| / |Z_1|.
Figure branch_figure(const std::string& title, const std::vector<NamedBranch>& branches);

/// Fig. 12: the time-integration sweep up and down over the HBM amplitude.
Figure sweep_figure(const std::string& title, const analysis::Branch& branch,
                    const analysis::AmplitudeSweep& sweep);

/// Fig. 17: the Poincaré sections of the map over the HBM orbit's z at the same phase (t = nT),
/// and the HBM amplitude below.
Figure map_figure(const std::string& title, const std::vector<NamedBranch>& branches,
                  const analysis::BifurcationMap& map);

}  // namespace oscilab::figures
