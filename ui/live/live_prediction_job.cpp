#include "ui/live/live_prediction_job.h"

#include <cmath>
#include <exception>
#include <string>

#include "analysis/model/reference_models.h"
#include "ui/background_job.h"
#include "ui/live/live_edc_plot_data.h"

namespace oscilab::ui {

/// The model's EDC at the prediction levels, both wells (written by the worker).
struct LivePredictionJob::Prediction {
  std::shared_ptr<const analysis::Model> model;
  double frequency_hz = 0.0;
  std::vector<double> levels_n;
  analysis::LevelResponse wells[2];  // positive, negative
  std::string error;
};

LivePredictionJob::LivePredictionJob(QObject* parent)
    : QObject(parent),
      job_(new BackgroundJob(this)),
      model_(std::make_shared<const analysis::Model>(analysis::paper_model())),
      label_(tr("paper model (Tables 1, 3)")) {
  connect(job_, &BackgroundJob::finished, this, &LivePredictionJob::on_job_finished);
}

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

bool LivePredictionJob::running() const { return job_->running(); }

void LivePredictionJob::start(double frequency_hz, double max_measured_f0_n) {
  if (!(frequency_hz > 0)) return;
  if (job_->running()) {
    again_ = true;
    return;
  }
  auto prediction = std::make_shared<Prediction>();
  prediction->model = model_;
  prediction->frequency_hz = frequency_hz;
  prediction->levels_n = prediction_levels(max_measured_f0_n);
  running_ = prediction;
  frequency_hz_ = frequency_hz;
  top_n_ = prediction->levels_n.back();
  again_ = false;
  job_->start([prediction](const ProgressFn&, const CancelToken& cancel) {
    // Harmonic balance of the model, level by level (a sweep up, §4.2), per well: milliseconds
    // each (measured: ~4 ms for 53 levels), so cancellation between wells suffices.
    try {
      for (int w = 0; w < 2 && !cancel.cancelled(); ++w) {
        prediction->wells[w] = analysis::level_response(
            *prediction->model, prediction->frequency_hz, w == 0, prediction->levels_n);
      }
    } catch (const std::exception& error) {
      prediction->error = error.what();
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

void LivePredictionJob::on_job_finished(bool cancelled) {
  if (cancelled || !running_) return;
  shown_ = running_;
  Q_EMIT finished();
}

}  // namespace oscilab::ui
