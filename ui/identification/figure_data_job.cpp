#include "ui/identification/figure_data_job.h"

#include "daq/recording/fit_json.h"

namespace oscilab::ui {

FigureDataJob::FigureDataJob(QObject* parent) : QObject(parent) {}

bool FigureDataJob::start(std::shared_ptr<const FitOutcome> fit,
                          std::shared_ptr<const figures::FitFigureData> existing,
                          std::string export_dir) {
  if (!fit || !fit->objective) return false;
  auto outcome = std::make_shared<FigureDataOutcome>();
  outcome->export_dir = export_dir;
  return work_.start(std::move(outcome), [fit = std::move(fit), existing = std::move(existing),
                                          dir = std::move(export_dir)](FigureDataOutcome& outcome,
                                                                       const ProgressFn&,
                                                                       const CancelToken& cancel) {
    auto data = std::make_shared<figures::FitFigureData>(
        existing ? *existing
                 : figures::fit_figure_data(*fit->objective, fit->fit.theta, 0, cancel));
    if (!dir.empty() && !cancel.cancelled()) {  // InputError: a file that cannot be written
      daq::write_fit_json(dir + "/fit.json", fit->fit, *fit->objective, fit->records, fit->notes);
      figures::write_fit_figures(dir, fit->fit, *fit->objective, *data, true);
    }
    outcome.data = std::move(data);
  });
}

}  // namespace oscilab::ui
