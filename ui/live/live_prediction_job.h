#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QObject>
#include <QString>

#include "analysis/hbm/level_response.h"
#include "analysis/model/model.h"
#include "ui/outcome_job.h"

namespace oscilab::ui {

/// The model's EDC against f₀ in both wells at the live frequency (the curve drawn over the
/// measured levels, Fig. 15), by harmonic balance on a worker thread (an OutcomeJob). One job
/// runs at a time: a start() while one runs is remembered and done once it finishes. Used from
/// the UI thread only.
class LivePredictionJob : public QObject {
  Q_OBJECT

 public:
  explicit LivePredictionJob(QObject* parent = nullptr);
  ~LivePredictionJob() override;

  /// The model predicted (default: the paper's, Tables 1 and 3) and its name in the legend.
  /// Forgets the prediction made: needed() is true again.
  void set_model(std::shared_ptr<const analysis::Model> model, const QString& label);
  const QString& model_label() const { return label_; }

  /// Whether the prediction drawn is stale: another ν, or levels measured past its largest.
  bool needed(double frequency_hz, double max_measured_f0_n) const;
  /// Predicts at ν over prediction_levels(max_measured_f0_n); nothing without a ν > 0.
  void start(double frequency_hz, double max_measured_f0_n);
  bool running() const { return work_.running(); }
  /// A start() came while the job ran: start again with the current ν and levels.
  bool again() const { return again_; }

  /// The EDC of the last prediction, positive well (0) and negative well (1); empty before one.
  const analysis::LevelResponse& well(int index) const;
  /// Why the last prediction failed, in part or whole; empty when it did not.
  QString message() const;

 Q_SIGNALS:
  /// A prediction finished (not cancelled): well() and message() hold it.
  void finished();

 private:
  /// The model's EDC at the prediction levels, both wells (written by the worker).
  struct Prediction {
    std::shared_ptr<const analysis::Model> model;
    double frequency_hz = 0.0;
    std::vector<double> levels_n;
    analysis::LevelResponse wells[2];  // positive, negative
    bool cancelled = false;
    std::string error;
  };
  void on_job_finished(std::shared_ptr<const Prediction> prediction);

  std::shared_ptr<const Prediction> shown_;  // the last one finished
  std::shared_ptr<const analysis::Model> model_;
  QString label_;
  double frequency_hz_ = 0.0;  // of the prediction drawn or running
  double top_n_ = 0.0;         // its largest level
  bool again_ = false;
  OutcomeJob<Prediction> work_{this, &LivePredictionJob::on_job_finished};
};

}  // namespace oscilab::ui
