#include "ui/identification_panel.h"

#include <chrono>
#include <cmath>
#include <exception>

#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "analysis/identification/campaign_model.h"
#include "analysis/identification/edc_dataset.h"
#include "analysis/model/reference_models.h"
#include "daq/recording/campaign_reader.h"
#include "ui/background_job.h"

namespace oscilab::ui {

/// What a job hands back to the UI thread (written by the worker, read after finished()).
struct IdentificationPanel::Outcome {
  bool diagnosis = false;
  std::string error;  // InputError text: bad recordings
  std::unique_ptr<analysis::EdcObjective> objective;
  analysis::FitResult fit;
  analysis::DiagnosisResult diagnosis_result;
};

namespace {

const QColor kWellColor[2] = {QColor(0, 114, 178), QColor(213, 94, 0)};  // z+*, z-*

QTableWidgetItem* cell(const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setFlags(item->flags() & ~Qt::ItemIsEditable);
  return item;
}

QString number(double value, int digits = 4) {
  return std::isfinite(value) ? QString::number(value, 'g', digits) : QStringLiteral("—");
}

}  // namespace

IdentificationPanel::IdentificationPanel(QWidget* parent) : QWidget(parent) {
  job_ = new BackgroundJob(this);
  connect(job_, &BackgroundJob::progress, this,
          [this](double f) { progress_->setValue(static_cast<int>(1000 * f)); });
  connect(job_, &BackgroundJob::finished, this, &IdentificationPanel::on_finished);

  auto* records = new QGroupBox(tr("Stepped-sine recordings (both wells)"));
  record_list_ = new QListWidget;
  record_list_->setObjectName("record_list");
  record_list_->setMaximumHeight(90);
  add_button_ = new QPushButton(tr("Add\u2026"));
  auto* remove_button = new QPushButton(tr("Remove"));
  connect(add_button_, &QPushButton::clicked, this, [this] {
    for (const QString& path : QFileDialog::getOpenFileNames(
             this, tr("Add recordings"), {},
             tr("Recordings (*.wav *.flac *.w64 *.rf64 *.aiff *.caf *.csv)"))) {
      add_recording(path.toStdString());
    }
  });
  connect(remove_button, &QPushButton::clicked, this,
          [this] { delete record_list_->takeItem(record_list_->currentRow()); });
  auto* record_buttons = new QHBoxLayout;
  record_buttons->addWidget(add_button_);
  record_buttons->addWidget(remove_button);
  auto* record_layout = new QVBoxLayout(records);
  record_layout->addWidget(record_list_);
  record_layout->addLayout(record_buttons);

  auto* settings = new QGroupBox(tr("Fit of \u03b8 = [f_d(z-*), f_d(z+*), f_d(0), v_t, k_s, c]"));
  method_box_ = new QComboBox;
  method_box_->addItem(tr("CMA-ES + BOBYQA polish"), "cmaes");
  method_box_->addItem(tr("genetic algorithm (paper)"), "ga");
  evaluations_box_ = new QSpinBox;
  evaluations_box_->setRange(10, 100000);
  evaluations_box_->setValue(2000);
  population_box_ = new QSpinBox;
  population_box_->setRange(2, 10000);
  population_box_->setValue(100);
  generations_box_ = new QSpinBox;
  generations_box_->setRange(0, 10000);
  generations_box_->setValue(20);
  auto* form = new QFormLayout(settings);
  form->addRow(tr("Method"), method_box_);
  form->addRow(tr("Evaluations (CMA-ES)"), evaluations_box_);
  form->addRow(tr("Population (GA)"), population_box_);
  form->addRow(tr("Generations (GA)"), generations_box_);

  fit_button_ = new QPushButton(tr("Fit"));
  fit_button_->setToolTip(tr("Identify the friction parameters from the EDCs (§4, §5)"));
  diagnose_button_ = new QPushButton(tr("Diagnose"));
  diagnose_button_->setToolTip(tr("Find the missing physical effect, add it, refit (or say none)"));
  cancel_button_ = new QPushButton(tr("Cancel"));
  cancel_button_->setEnabled(false);
  connect(fit_button_, &QPushButton::clicked, this, &IdentificationPanel::start_fit);
  connect(diagnose_button_, &QPushButton::clicked, this, &IdentificationPanel::start_diagnosis);
  connect(cancel_button_, &QPushButton::clicked, this, &IdentificationPanel::cancel);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(fit_button_);
  buttons->addWidget(diagnose_button_);
  buttons->addWidget(cancel_button_);
  progress_ = new QProgressBar;
  progress_->setRange(0, 1000);
  progress_->setTextVisible(false);
  status_label_ = new QLabel(tr("Add the recordings of both wells, then Fit or Diagnose."));
  status_label_->setWordWrap(true);
  verdict_label_ = new QLabel;
  verdict_label_->setObjectName("verdict");
  verdict_label_->setWordWrap(true);

  parameter_table_ = new QTableWidget(0, 5);
  parameter_table_->setHorizontalHeaderLabels(
      {tr("parameter"), tr("value"), tr("std error"), tr("95 % interval"), tr("note")});
  parameter_table_->horizontalHeader()->setStretchLastSection(true);
  parameter_table_->verticalHeader()->hide();
  step_table_ = new QTableWidget(0, 5);
  step_table_->setHorizontalHeaderLabels({tr("effect"), tr("\u0394BIC"), tr("cost before [mJ]"),
                                          tr("cost after [mJ]"), tr("candidates (\u0394BIC)")});
  step_table_->horizontalHeader()->setStretchLastSection(true);
  step_table_->verticalHeader()->hide();

  edc_plot_ = new QCustomPlot;
  edc_plot_->setMinimumHeight(260);
  edc_plot_->xAxis->setLabel(tr("forcing amplitude f0 [N]"));
  edc_plot_->yAxis->setLabel(tr("EDC [mJ]"));
  edc_plot_->legend->setVisible(true);
  edc_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  residual_plot_ = new QCustomPlot;
  residual_plot_->setMinimumHeight(200);
  residual_plot_->xAxis->setLabel(tr("forcing amplitude f0 [N]"));
  residual_plot_->yAxis->setLabel(tr("(S_mes - S_mod) / \u03c3"));
  residual_plot_->legend->setVisible(true);

  convergence_plot_ = new QCustomPlot;
  convergence_plot_->xAxis->setLabel(tr("model evaluations"));
  convergence_plot_->yAxis->setLabel(tr("best \u03c7\u00b2 (log scale)"));
  convergence_plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
  convergence_plot_->yAxis->setTicker(QSharedPointer<QCPAxisTickerLog>::create());
  convergence_plot_->addGraph()->setPen(QPen(kWellColor[0], 2));

  auto* diagnosis_page = new QWidget;
  auto* diagnosis_layout = new QVBoxLayout(diagnosis_page);
  diagnosis_layout->addWidget(verdict_label_);
  diagnosis_layout->addWidget(step_table_, 1);
  diagnosis_layout->addWidget(residual_plot_, 2);
  tabs_ = new QTabWidget;
  tabs_->addTab(edc_plot_, tr("EDC"));
  tabs_->addTab(parameter_table_, tr("Parameters"));
  tabs_->addTab(convergence_plot_, tr("Convergence"));
  tabs_->addTab(diagnosis_page, tr("Diagnosis"));

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(records);
  layout->addWidget(settings);
  layout->addLayout(buttons);
  layout->addWidget(progress_);
  layout->addWidget(status_label_);
  layout->addWidget(tabs_, 1);
}

IdentificationPanel::~IdentificationPanel() = default;

void IdentificationPanel::set_recordings(const std::vector<std::string>& paths) {
  record_list_->clear();
  for (const auto& p : paths) add_recording(p);
}

void IdentificationPanel::add_recording(const std::string& path) {
  const QString q = QString::fromStdString(path);
  for (int i = 0; i < record_list_->count(); ++i) {
    if (record_list_->item(i)->data(Qt::UserRole).toString() == q) return;
  }
  auto* item = new QListWidgetItem(QFileInfo(q).fileName());
  item->setData(Qt::UserRole, q);
  item->setToolTip(q);
  record_list_->addItem(item);
}

std::vector<std::string> IdentificationPanel::recordings() const {
  std::vector<std::string> out;
  for (int i = 0; i < record_list_->count(); ++i) {
    out.push_back(record_list_->item(i)->data(Qt::UserRole).toString().toStdString());
  }
  return out;
}

void IdentificationPanel::set_fit_settings(const std::string& method, int evaluations,
                                           int population, int generations) {
  method_box_->setCurrentIndex(std::max(0, method_box_->findData(QString::fromStdString(method))));
  evaluations_box_->setValue(evaluations);
  population_box_->setValue(population);
  generations_box_->setValue(generations);
}

void IdentificationPanel::set_diagnosis_budget(long baseline_evaluations,
                                               long candidate_evaluations) {
  baseline_evaluations_ = baseline_evaluations;
  candidate_evaluations_ = candidate_evaluations;
}

bool IdentificationPanel::busy() const { return job_->running(); }

void IdentificationPanel::start_fit() { start(false); }
void IdentificationPanel::start_diagnosis() { start(true); }

void IdentificationPanel::cancel() {
  job_->cancel();
  status_label_->setText(tr("Cancelling\u2026"));
}

void IdentificationPanel::set_busy(bool busy) {
  fit_button_->setEnabled(!busy);
  diagnose_button_->setEnabled(!busy);
  add_button_->setEnabled(!busy);
  cancel_button_->setEnabled(busy);
  if (busy) progress_->setValue(0);
}

void IdentificationPanel::add_convergence_point(long evaluations, double best_weighted_cost) {
  if (!(best_weighted_cost > 0.0) || !std::isfinite(best_weighted_cost)) return;
  convergence_plot_->graph(0)->addData(static_cast<double>(evaluations), best_weighted_cost);
  convergence_plot_->rescaleAxes();
  convergence_plot_->replot(QCustomPlot::rpQueuedReplot);
}

void IdentificationPanel::start(bool diagnosis) {
  const std::vector<std::string> paths = recordings();
  if (paths.empty()) {
    status_label_->setText(tr("No recordings: add the stepped-sine records of both wells."));
    return;
  }
  auto outcome = std::make_shared<Outcome>();
  outcome->diagnosis = diagnosis;
  analysis::FitOptions fit_options;
  fit_options.method = method_box_->currentData().toString() == "ga" ? analysis::FitMethod::Genetic
                                                                     : analysis::FitMethod::Cmaes;
  fit_options.max_evaluations = evaluations_box_->value();
  fit_options.genetic.population = population_box_->value();
  fit_options.genetic.generations = generations_box_->value();
  fit_options.genetic.elite =
      std::max(1, static_cast<int>(std::lround(0.05 * population_box_->value())));
  analysis::DiagnosisOptions diagnosis_options;
  diagnosis_options.baseline_evaluations = baseline_evaluations_;
  diagnosis_options.candidate_evaluations = candidate_evaluations_;
  outcome_ = outcome;
  convergence_plot_->graph(0)->data()->clear();
  set_busy(true);
  QPointer<IdentificationPanel> self(this);
  status_label_->setText(diagnosis ? tr("Diagnosing\u2026") : tr("Fitting\u2026"));
  job_->start([outcome, paths, fit_options, diagnosis_options, self](const ProgressFn& progress,
                                                                     const CancelToken& cancel) {
    try {
      const analysis::CampaignAnalysis campaign =
          daq::analyze_recordings(paths, {}, {}, {}, cancel);
      std::vector<std::string> notes;
      const analysis::Model base = analysis::campaign_model(
          analysis::paper_model(), campaign, analysis::StiffnessSource::Model, notes);
      const analysis::ModelForm form = analysis::ModelForm::paper(base);
      if (outcome->diagnosis) {
        outcome->diagnosis_result =
            analysis::diagnose(campaign, form, diagnosis_options, progress, cancel);
        const auto& r = outcome->diagnosis_result;
        if (r.final_form) {
          outcome->objective = std::make_unique<analysis::EdcObjective>(
              *r.final_form, analysis::edc_dataset(campaign), diagnosis_options.cost);
        }
      } else {
        outcome->objective = std::make_unique<analysis::EdcObjective>(
            form, analysis::edc_dataset(campaign), analysis::EdcCostSettings{});
        const long budget = fit_options.method == analysis::FitMethod::Genetic
                                ? static_cast<long>(fit_options.genetic.population) *
                                      (fit_options.genetic.generations + 1)
                                : fit_options.max_evaluations;
        // The convergence curve gets a point at most every 50 ms (20 redraws a second).
        auto last_point = std::chrono::steady_clock::now() - std::chrono::seconds(1);
        outcome->fit = analysis::fit_edc(
            *outcome->objective, fit_options,
            [&](const analysis::FitProgress& p) {
              if (p.stage == "uncertainty") return;
              progress(std::min(0.95, static_cast<double>(p.evaluations) / budget));
              const auto now = std::chrono::steady_clock::now();
              if (now - last_point < std::chrono::milliseconds(50)) return;
              last_point = now;
              QMetaObject::invokeMethod(
                  self.data(),
                  [self, evaluations = p.evaluations, cost = p.best_weighted_cost] {
                    if (self) self->add_convergence_point(evaluations, cost);
                  },
                  Qt::QueuedConnection);
            },
            cancel);
      }
    } catch (const InputError& error) {
      outcome->error = error.what();
    } catch (const std::exception& error) {
      outcome->error = std::string("internal error: ") + error.what();
    }
  });
}

void IdentificationPanel::on_finished(bool cancelled) {
  set_busy(false);
  progress_->setValue(1000);
  const std::shared_ptr<Outcome> outcome = outcome_;
  QString message;
  if (!outcome->error.empty()) {
    message = tr("Error: %1").arg(QString::fromStdString(outcome->error));
  } else if (cancelled) {
    message = tr("Cancelled.");
  } else if (outcome->diagnosis) {
    show_diagnosis(*outcome);
    message = tr("Diagnosis: %1 (%2 s)")
                  .arg(QString::fromStdString(outcome->diagnosis_result.verdict))
                  .arg(outcome->diagnosis_result.seconds, 0, 'f', 1);
  } else {
    show_fit(*outcome);
    message = tr("Fit: %1 evaluations in %2 s, cost eq. (8) %3 mJ, mean deviation %4 % / %5 %")
                  .arg(outcome->fit.evaluations)
                  .arg(outcome->fit.seconds, 0, 'f', 1)
                  .arg(1e3 * outcome->fit.evaluation.cost_j, 0, 'g', 4)
                  .arg(outcome->fit.evaluation.mean_deviation_pct_positive, 0, 'f', 2)
                  .arg(outcome->fit.evaluation.mean_deviation_pct_negative, 0, 'f', 2);
    const double floor = outcome->objective ? outcome->objective->settings().model_error_rel : 0.0;
    if (outcome->fit.check_harmonics > 0 && outcome->fit.truncation_change_rel > 0.5 * floor) {
      message += tr(". Harmonic balance truncation: S_mod changes by %1 % at H = %2, comparable "
                    "to the %3 % model-error floor: parameters may absorb it.")
                     .arg(100.0 * outcome->fit.truncation_change_rel, 0, 'f', 2)
                     .arg(outcome->fit.check_harmonics)
                     .arg(100.0 * floor, 0, 'g', 2);
    }
  }
  status_label_->setText(message);
  Q_EMIT job_finished(message);
}

void IdentificationPanel::show_fit(const Outcome& outcome) {
  const analysis::FitResult& fit = outcome.fit;
  parameter_table_->setRowCount(static_cast<int>(fit.names.size()));
  for (int i = 0; i < static_cast<int>(fit.names.size()); ++i) {
    parameter_table_->setItem(i, 0, cell(QString::fromStdString(fit.names[i])));
    parameter_table_->setItem(i, 1, cell(number(fit.theta(i), 5)));
    if (i < static_cast<int>(fit.uncertainty.parameters.size())) {
      const auto& u = fit.uncertainty.parameters[i];
      parameter_table_->setItem(i, 2, cell(number(u.standard_error, 3)));
      parameter_table_->setItem(
          i, 3, cell(QStringLiteral("[%1, %2]").arg(number(u.lower_95), number(u.upper_95))));
      parameter_table_->setItem(i, 4, cell(QString::fromStdString(u.note)));
    }
  }
  parameter_table_->resizeColumnsToContents();
  // The whole history replaces the live points (which were thinned to 20 a second).
  QVector<double> evaluations, best;
  for (const auto& [e, cost] : fit.history) {
    if (!(cost > 0.0) || !std::isfinite(cost)) continue;
    evaluations.push_back(static_cast<double>(e));
    best.push_back(cost);
  }
  convergence_plot_->graph(0)->setData(evaluations, best);
  convergence_plot_->rescaleAxes();
  convergence_plot_->replot();
  if (outcome.objective) plot_edc(*outcome.objective, fit.evaluation, tr("model"));
  tabs_->setCurrentIndex(0);
}

void IdentificationPanel::show_diagnosis(const Outcome& outcome) {
  const analysis::DiagnosisResult& r = outcome.diagnosis_result;
  verdict_label_->setText(
      tr("<b>Verdict: %1</b> &nbsp; baseline cost %2 mJ (\u03c7\u00b2/\u03bd %3, noise level "
         "%4) \u2192 final %5 mJ (\u03c7\u00b2/\u03bd %6)")
          .arg(QString::fromStdString(r.verdict))
          .arg(1e3 * r.baseline.evaluation.cost_j, 0, 'g', 4)
          .arg(r.baseline_maps.reduced_chi2, 0, 'g', 3)
          .arg(r.noise_reduced_chi2, 0, 'g', 3)
          .arg(1e3 * r.final_evaluation.cost_j, 0, 'g', 4)
          .arg(r.final_maps.reduced_chi2, 0, 'g', 3));
  step_table_->setRowCount(static_cast<int>(r.steps.size()));
  for (int i = 0; i < static_cast<int>(r.steps.size()); ++i) {
    const auto& s = r.steps[i];
    QString tried;
    for (const auto& t : s.trials) {
      tried += QStringLiteral("%1%2 %3")
                   .arg(tried.isEmpty() ? "" : ", ")
                   .arg(QString::fromStdString(t.effect))
                   .arg(t.delta_bic, 0, 'f', 0);
    }
    step_table_->setItem(i, 0, cell(QString::fromStdString(s.effect)));
    step_table_->setItem(i, 1, cell(s.effect == "none" ? "—" : number(s.delta_bic, 4)));
    step_table_->setItem(i, 2, cell(number(1e3 * s.cost_before_j)));
    step_table_->setItem(i, 3, cell(s.effect == "none" ? "—" : number(1e3 * s.cost_after_j)));
    step_table_->setItem(i, 4, cell(tried));
  }
  step_table_->resizeColumnsToContents();

  residual_plot_->clearGraphs();
  const auto add = [&](const analysis::DiscrepancyMaps& maps, bool positive, const QString& name,
                       QCPScatterStyle::ScatterShape shape) {
    QVector<double> x, y;
    for (const auto& d : maps.levels) {
      if (d.positive_well != positive) continue;
      x.push_back(d.f0_n);
      y.push_back(d.residual_sigma);
    }
    if (x.isEmpty()) return;
    QCPGraph* g = residual_plot_->addGraph();
    g->setName(name);
    g->setData(x, y);
    g->setLineStyle(QCPGraph::lsNone);
    g->setPen(QPen(kWellColor[positive ? 0 : 1]));
    g->setScatterStyle(QCPScatterStyle(shape, 7));
  };
  add(r.baseline_maps, true, tr("z+* baseline"), QCPScatterStyle::ssCircle);
  add(r.baseline_maps, false, tr("z-* baseline"), QCPScatterStyle::ssCircle);
  add(r.final_maps, true, tr("z+* final"), QCPScatterStyle::ssDisc);
  add(r.final_maps, false, tr("z-* final"), QCPScatterStyle::ssDisc);
  residual_plot_->rescaleAxes();
  residual_plot_->xAxis->scaleRange(1.08);  // keep the edge points off the frame
  residual_plot_->yAxis->scaleRange(1.25);  // and room for the legend
  residual_plot_->replot();
  if (outcome.objective) {
    plot_edc(*outcome.objective, r.final_evaluation,
             tr("model (%1)").arg(QString::fromStdString(r.verdict)));
  }
  tabs_->setCurrentIndex(2);
}

void IdentificationPanel::plot_edc(const analysis::EdcObjective& objective,
                                   const analysis::EdcEvaluation& model,
                                   const QString& model_name) {
  edc_plot_->clearGraphs();
  const auto& groups = objective.data().groups;
  for (std::size_t g = 0; g < groups.size() && g < model.edc_mod_j.size(); ++g) {
    const bool positive = groups[g].positive_well;
    const QString well = positive ? tr("z+* well") : tr("z-* well");
    QVector<double> f0, measured, error, predicted;
    for (std::size_t i = 0; i < groups[g].levels.size(); ++i) {
      const auto& m = groups[g].levels[i];
      f0.push_back(m.f0_n);
      measured.push_back(1e3 * m.edc_j);
      error.push_back(3e3 * m.edc_std_j);  // ±3σ as the paper's Fig. 10
      predicted.push_back(1e3 * model.edc_mod_j[g][i]);
    }
    QCPGraph* points = edc_plot_->addGraph();
    points->setName(well + tr(" measured \u00b13\u03c3"));
    points->setData(f0, measured);
    points->setLineStyle(QCPGraph::lsNone);
    points->setPen(QPen(kWellColor[positive ? 0 : 1]));
    points->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, 6));
    auto* bars = new QCPErrorBars(edc_plot_->xAxis, edc_plot_->yAxis);
    bars->removeFromLegend();
    bars->setDataPlottable(points);
    bars->setData(error);
    bars->setPen(QPen(kWellColor[positive ? 0 : 1]));
    QCPGraph* line = edc_plot_->addGraph();
    line->setName(well + " " + model_name);
    line->setData(f0, predicted);
    QPen pen(kWellColor[positive ? 0 : 1], 2, Qt::DashLine);
    line->setPen(pen);
  }
  edc_plot_->rescaleAxes();
  edc_plot_->xAxis->scaleRange(1.08);
  edc_plot_->yAxis->setRangeLower(0.0);
  edc_plot_->replot();
}

}  // namespace oscilab::ui
