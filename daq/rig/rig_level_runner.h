#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "analysis/design/adaptive_test.h"
#include "analysis/model/model.h"

namespace oscilab::daq {

/// The virtual rig as an adaptive test's level runner: each run a stepped sine of the rig's model
/// (record_stepped_sine, as fast as it computes), written to `folder` as
/// `NN_<purpose>_<well>.wav` with its sidecar, and handed back as the file reads. The rig's seed
/// of run N is seed × 1000 + N, so a test is reproducible for its seed.
class RigLevelRunner : public analysis::LevelRunner {
 public:
  struct Schedule {
    double hold_s = 10.0;    // per level
    double ramp_s = 1.0;     // amplitude ramp at the start of a level
    double lead_in_s = 2.5;  // at rest before each run
  };

  /// `folder` must exist.
  RigLevelRunner(analysis::Model truth, std::string folder, Schedule schedule, std::uint64_t seed);

  analysis::LevelRun run(const std::vector<double>& levels_n, double freq_hz, bool positive_well,
                         const std::string& purpose) override;

  /// The recordings written, in order.
  const std::vector<std::string>& paths() const { return paths_; }

 private:
  analysis::Model truth_;
  std::string folder_;
  Schedule schedule_;
  std::uint64_t seed_;
  std::vector<std::string> paths_;
};

}  // namespace oscilab::daq
