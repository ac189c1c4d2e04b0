#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QObject>

#include "analysis/hbm/branch.h"
#include "analysis/hbm/continuation.h"
#include "analysis/model/model.h"
#include "analysis/simulation/bifurcation_map.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// What a bifurcation map hands back when it ends (finished, cancelled or failed).
struct BifurcationMapOutcome {
  bool cancelled = false;
  std::string error;                       // InputError text: options the core rejects
  std::vector<analysis::Branch> branches;  // the HBM branches the map is drawn over
  analysis::BifurcationMap map;
};

/// The bifurcation map of a model by time simulation (analysis::bifurcation_map, Fig. 17) over
/// its HBM branches (continue_branches, first: a tenth of the progress bar), on a worker thread
/// (ui/outcome_job.h) with progress and cancel. Thread-safety: UI thread only.
class BifurcationMapJob : public QObject {
  Q_OBJECT

 public:
  explicit BifurcationMapJob(QObject* parent = nullptr);

  /// Returns false (and does nothing) while one runs.
  bool start(std::shared_ptr<const analysis::Model> model,
             std::vector<analysis::ContinuationOptions> continuations,
             analysis::BifurcationMapOptions map);
  void cancel() { work_.cancel(); }
  bool running() const { return work_.running(); }

 Q_SIGNALS:
  void progress(double fraction_done);
  /// The map ended (UI thread).
  void finished(std::shared_ptr<const oscilab::ui::BifurcationMapOutcome> outcome);

 private:
  OutcomeJob<BifurcationMapOutcome> work_{this, &BifurcationMapJob::finished,
                                          &BifurcationMapJob::progress};
};

}  // namespace oscilab::ui
