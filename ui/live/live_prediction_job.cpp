#include "ui/live/live_prediction_job.h"

#include <cmath>
#include <string>

#include "analysis/model/reference_models.h"
#include "ui/live/live_edc_plot_data.h"

namespace oscilab::ui {

LivePredictionJob::LivePredictionJob(QObject* parent)
    : QObject(parent),
      model_(std::make_shared<const analysis::Model>(analysis::paper_model())),
      label_(tr("paper model (Tables 1, 3)")) {}

LivePredictionJob::~LivePredictionJob() = default;

void LivePredictionJob::set_model(std::shared_ptr<const analysis::Model> model,
                                  const QString& label) {
  if (!model) return;
  model_ = std::move(model);
  label_ = label;
  shown_.reset();
  frequency_hz_ = 0.0;  // recompute at the next frame
}

bool LivePredictionJob::needed(double frequency_hz, double max_measured_f0_n) const {
  return frequency_hz > 0 &&
         (std::abs(frequency_hz - frequency_hz_) > 1e-9 || max_measured_f0_n > top_n_ + 1e-9);
}

void LivePredictionJob::start(double frequency_hz, double max_measured_f0_n) {
  if (!(frequency_hz > 0)) return;
  if (work_.running()) {
    again_ = true;
    return;
  }
  auto prediction = std::make_shared<Prediction>();
  prediction->model = model_;
  prediction->frequency_hz = frequency_hz;
  prediction->levels_n = prediction_levels(max_measured_f0_n);
  frequency_hz_ = frequency_hz;
  top_n_ = prediction->levels_n.back();
  again_ = false;
  work_.start(
      std::move(prediction), [](Prediction& p, const ProgressFn&, const CancelToken& cancel) {
        // Harmonic balance of the model, level by level (a sweep up, §4.2), per well: milliseconds
        // each (measured: ~4 ms for 53 levels), so cancellation between wells suffices.
        for (int w = 0; w < 2 && !cancel.cancelled(); ++w) {
          p.wells[w] = analysis::level_response(*p.model, p.frequency_hz, w == 0, p.levels_n);
        }
      });
}

const analysis::LevelResponse& LivePredictionJob::well(int index) const {
  static const analysis::LevelResponse kNone;
  return shown_ ? shown_->wells[index == 0 ? 0 : 1] : kNone;
}

QString LivePredictionJob::message() const {
  if (!shown_) return {};
  if (!shown_->error.empty()) {
    return tr("Model prediction failed: %1").arg(QString::fromStdString(shown_->error));
  }
  for (int w = 0; w < 2; ++w) {
    const analysis::LevelResponse& r = shown_->wells[w];
    if (r.status != JobStatus::Ok) {
      return tr("Model prediction (%1 well): %2")
          .arg(w == 0 ? tr("z\u208a*") : tr("z\u208b*"))
          .arg(QString::fromStdString(r.message));
    }
  }
  return {};
}

void LivePredictionJob::on_job_finished(std::shared_ptr<const Prediction> prediction) {
  if (prediction->cancelled) return;
  shown_ = std::move(prediction);
  Q_EMIT finished();
}

}  // namespace oscilab::ui
