#include "ui/identification/identification_panel.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSplitter>
#include <QTabBar>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "analysis/figures/fit_figures.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/reference_models.h"
#include "ui/flow_layout.h"
#include "ui/identification/diagnosis_job.h"
#include "ui/identification/diagnosis_view.h"
#include "ui/identification/figure_data_job.h"
#include "ui/identification/figure_dialog.h"
#include "ui/identification/fit_settings_form.h"
#include "ui/identification/response_dialog.h"
#include "ui/plots/plot_helpers.h"
#include "ui/plots/well_colours.h"
#include "ui/table_cells.h"

namespace oscilab::ui {

namespace {

// A parameter of θ as Table 3 names it, with its unit (other forms' names as they are).
QString table3_label(const std::string& name) {
  if (name == "fd_zminus_n") return QStringLiteral("f_d(z\u208b*) [N]");
  if (name == "fd_zero_n") return QStringLiteral("f_d(0) [N]");
  if (name == "fd_zplus_n") return QStringLiteral("f_d(z\u208a*) [N]");
  if (name == "ks") return QStringLiteral("k_s [-]");
  if (name == "c_ns_m") return QStringLiteral("c [N s/m]");
  if (name == "vt_m_s") return QStringLiteral("v_t [m/s]");
  return QString::fromStdString(name);
}

// Tab names of the fit's figures (analysis/figures/fit_figures.h stems).
QString figure_tab_name(const std::string& stem) {
  if (stem == "edc_fit") return QObject::tr("EDC (Fig. 15)");
  if (stem == "convergence") return QObject::tr("Convergence (Fig. 14)");
  if (stem == "friction") return QObject::tr("Friction f_d(z)");
  if (stem == "cost_slices") return QObject::tr("Cost slices (Fig. 13)");
  if (stem == "sensitivity_positive") return QObject::tr("Sensitivity z\u208a* (Fig. 16)");
  if (stem == "sensitivity_negative") return QObject::tr("Sensitivity z\u208b* (Fig. 16)");
  return QString::fromStdString(stem);
}

}  // namespace

void IdentificationPanel::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  if (splitter_placed_ || splitter_->height() < 100) return;  // the user placed the divider
  // The set-up gets what its contents ask for (its scroll area's hint stops at 24 lines) up to a
  // third of the height, again as the panel grows, until the user moves the divider.
  const int total = splitter_->height() - splitter_->handleWidth();
  const int setup = std::min(setup_->sizeHint().height(), total / 3);
  splitter_->setSizes({setup, total - setup});
}

// The fit's worker emits fit_preview on this object: the workers must have ended before anything
// of the panel goes (the jobs' destructors cancel and join).
IdentificationPanel::~IdentificationPanel() {
  delete fit_job_;
  delete diagnosis_job_;
  delete figure_data_job_;
}

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
  settings_form_->set_search(method, evaluations, population, generations);
}

void IdentificationPanel::set_diagnosis_budget(long baseline_evaluations,
                                               long candidate_evaluations) {
  baseline_evaluations_ = baseline_evaluations;
  candidate_evaluations_ = candidate_evaluations;
}

bool IdentificationPanel::busy() const {
  return fit_job_->running() || diagnosis_job_->running() || figure_data_job_->running();
}

void IdentificationPanel::cancel() {
  fit_job_->cancel();
  diagnosis_job_->cancel();
  figure_data_job_->cancel();
  status_label_->setText(tr("Cancelling\u2026"));
}

void IdentificationPanel::set_busy(bool busy) {
  fit_button_->setEnabled(!busy);
  diagnose_button_->setEnabled(!busy);
  add_button_->setEnabled(!busy);
  cancel_button_->setEnabled(busy);
  if (busy) progress_->setValue(0);
  progress_->setVisible(busy);
  update_result_buttons();
}

void IdentificationPanel::update_result_buttons() {
  const bool ready = fitted_ != nullptr && !cancel_button_->isEnabled();  // and not busy
  figures_button_->setEnabled(ready);
  export_button_->setEnabled(ready);
  branch_button_->setEnabled(fitted_ != nullptr);  // the dialogs have workers of their own
  map_button_->setEnabled(fitted_ != nullptr);
}

const analysis::FitResult* IdentificationPanel::fit_result() const {
  return fitted_ ? &fitted_->fit : nullptr;
}

std::shared_ptr<const analysis::EdcObjective> IdentificationPanel::fit_objective() const {
  return fitted_ ? fitted_->objective : nullptr;
}

void IdentificationPanel::add_convergence_point(long evaluations, double best_weighted_cost) {
  if (!(best_weighted_cost > 0.0) || !std::isfinite(best_weighted_cost)) return;
  convergence_plot_->graph(0)->addData(static_cast<double>(evaluations), best_weighted_cost);
  convergence_plot_->rescaleAxes();
  convergence_plot_->replot(QCustomPlot::rpQueuedReplot);
}

bool IdentificationPanel::job_inputs(std::vector<std::string>& paths, analysis::FitSetup& setup) {
  if (busy()) return false;
  paths = recordings();
  if (paths.empty()) {
    status_label_->setText(tr("No recordings: add the stepped-sine records of both wells."));
    return false;
  }
  try {
    setup = settings_form_->fit_setup();
  } catch (const InputError& error) {  // a model file that cannot be read
    status_label_->setText(tr("Error: %1").arg(QString::fromStdString(error.what())));
    return false;
  }
  return true;
}

void IdentificationPanel::start_fit() {
  std::vector<std::string> paths;
  analysis::FitSetup setup;
  if (!job_inputs(paths, setup)) return;
  const analysis::FitOptions options = settings_form_->fit_options();
  try {
    analysis::validate(options, "");
  } catch (const InputError& error) {
    status_label_->setText(tr("Error: %1").arg(QString::fromStdString(error.what())));
    return;
  }
  begin_job(tr("Fitting\u2026"));
  fit_job_->start(std::move(paths), std::move(setup), options);
}

void IdentificationPanel::start_diagnosis() {
  std::vector<std::string> paths;
  analysis::FitSetup setup;
  if (!job_inputs(paths, setup)) return;
  analysis::DiagnosisOptions options;
  options.baseline_evaluations = baseline_evaluations_;
  options.candidate_evaluations = candidate_evaluations_;
  begin_job(tr("Diagnosing\u2026"));
  diagnosis_job_->start(std::move(paths), std::move(setup), options);
}

void IdentificationPanel::begin_job(const QString& status) {
  convergence_plot_->graph(0)->data()->clear();
  progress_->setRange(0, 1000);
  progress_->setTextVisible(false);  // a diagnosis says its stage on the bar once it has one
  set_busy(true);
  status_label_->setText(status);
}

QString IdentificationPanel::ended_text(const std::string& error, bool cancelled) const {
  if (!error.empty()) return tr("Error: %1").arg(QString::fromStdString(error));
  return cancelled ? tr("Cancelled.") : QString();
}

void IdentificationPanel::end_job(bool completed) {
  set_busy(false);
  if (completed) progress_->setValue(1000);  // a cancelled or failed job keeps what it reached
}

void IdentificationPanel::on_fit_finished(std::shared_ptr<const FitOutcome> outcome) {
  if (!outcome->cancelled && outcome->error.empty() &&
      outcome->fit.status != JobStatus::Cancelled) {
    fitted_ = outcome;  // the figures and dialogs follow the new fit
    figure_data_.reset();
  }
  end_job(fitted_ == outcome);
  QString message = ended_text(outcome->error, outcome->cancelled);
  if (message.isEmpty()) {
    show_fit(*outcome);
    // A well without levels has no deviation (NaN).
    const auto deviation = [this](double pct) {
      return std::isfinite(pct) ? QString("%1 %").arg(pct, 0, 'f', 2) : tr("no levels");
    };
    message = tr("Fit: %1 evaluations in %2 s, cost eq. (8) %3 mJ, mean deviation %4 / %5")
                  .arg(outcome->fit.evaluations)
                  .arg(outcome->fit.seconds, 0, 'f', 1)
                  .arg(1e3 * outcome->fit.evaluation.cost_j, 0, 'g', 4)
                  .arg(deviation(outcome->fit.evaluation.mean_deviation_pct_positive),
                       deviation(outcome->fit.evaluation.mean_deviation_pct_negative));
    const std::string warning =
        outcome->objective ? analysis::truncation_warning(outcome->fit, *outcome->objective) : "";
    if (!warning.empty()) message += ". Warning: " + QString::fromStdString(warning) + ".";
  }
  status_label_->setText(message);
  if (fitted_ == outcome && outcome->objective && outcome->fit.theta.size() > 0) {
    try {
      Q_EMIT model_fitted(std::make_shared<const analysis::Model>(
          outcome->objective->form().build(outcome->fit.theta)));
    } catch (const std::exception&) {  // a form that cannot build θ̄: nothing to hand on
    }
  }
  Q_EMIT job_finished(message);
}

void IdentificationPanel::on_diagnosis_finished(std::shared_ptr<const DiagnosisOutcome> outcome) {
  end_job(!outcome->cancelled && outcome->error.empty());
  QString message = ended_text(outcome->error, outcome->cancelled);
  if (message.isEmpty()) {
    show_diagnosis(*outcome);
    message = tr("Diagnosis: %1 (%2 s)")
                  .arg(QString::fromStdString(outcome->result.verdict))
                  .arg(outcome->result.seconds, 0, 'f', 1);
  }
  status_label_->setText(message);
  Q_EMIT job_finished(message);
}

void IdentificationPanel::show_fit(const FitOutcome& outcome) {
  const analysis::FitResult& fit = outcome.fit;
  parameter_table_->setRowCount(static_cast<int>(fit.names.size()));
  for (int i = 0; i < static_cast<int>(fit.names.size()); ++i) {
    QTableWidgetItem* name = read_only_cell(table3_label(fit.names[i]));
    name->setToolTip(QString::fromStdString(fit.names[i]));  // its key in the FIT JSON
    name->setData(Qt::UserRole, QString::fromStdString(fit.names[i]));
    parameter_table_->setItem(i, 0, name);
    parameter_table_->setItem(i, 1, read_only_cell(number_text(fit.theta(i), 5)));
    if (i < static_cast<int>(fit.uncertainty.parameters.size())) {
      const auto& u = fit.uncertainty.parameters[i];
      parameter_table_->setItem(i, 2, read_only_cell(number_text(u.standard_error, 3)));
      parameter_table_->setItem(
          i, 3,
          read_only_cell(
              QStringLiteral("[%1, %2]").arg(number_text(u.lower_95), number_text(u.upper_95))));
      parameter_table_->setItem(i, 4, read_only_cell(QString::fromStdString(u.note)));
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
  if (outcome.objective) plot_edc(*outcome.objective, fit.evaluation.edc_mod_j, tr("model"));
  tabs_->setCurrentIndex(0);
}

void IdentificationPanel::show_diagnosis(const DiagnosisOutcome& outcome) {
  const analysis::DiagnosisResult& r = outcome.result;
  diagnosis_view_->show_result(r, bic_threshold_);
  if (outcome.objective) {
    plot_edc(*outcome.objective, r.final_evaluation.edc_mod_j,
             tr("model (%1)").arg(QString::fromStdString(r.verdict)));
  }
  tabs_->setCurrentWidget(diagnosis_view_);
}

void IdentificationPanel::show_preview(std::shared_ptr<const FitPreview> preview) {
  // A preview queued before its fit ended arrives before the fit's result; one of an older job
  // is dropped.
  if (!preview || !fit_job_->is_current(*preview)) return;
  plot_edc(*preview->objective, preview->edc_mod_j,
           tr("best so far (%1 evaluations)").arg(preview->evaluations));
}

void IdentificationPanel::show_measured(const analysis::EdcDataset& data, const QString& error) {
  if (busy() || model_drawn_) return;
  plot_edc(data.groups, {}, {});
  if (!error.isEmpty()) {
    status_label_->setText(tr("Nothing to fit: %1").arg(error));
    return;
  }
  const analysis::EdcGroup* positive = data.group(true);
  const analysis::EdcGroup* negative = data.group(false);
  const auto count = [](const analysis::EdcGroup* g) { return g ? int(g->levels.size()) : 0; };
  if (positive && negative) {
    status_label_->setText(
        tr("Measured: %1 levels around z\u208a*, %2 around z\u208b*. Fit identifies the friction "
           "from both; Diagnose looks for what the model misses.")
            .arg(count(positive))
            .arg(count(negative)));
  } else {
    status_label_->setText(
        tr("Measured: %1 levels around %2 only. Add a recording of the %3 well for the paper's "
           "fit of both wells, or Fit this one.")
            .arg(count(positive ? positive : negative))
            .arg(positive ? tr("z\u208a*") : tr("z\u208b*"))
            .arg(positive ? tr("z\u208b*") : tr("z\u208a*")));
  }
}

void IdentificationPanel::plot_edc(const analysis::EdcObjective& objective,
                                   const std::vector<std::vector<double>>& edc_mod_j,
                                   const QString& model_name) {
  model_drawn_ = true;
  plot_edc(objective.data().groups, edc_mod_j, model_name);
}

void IdentificationPanel::plot_edc(const std::vector<analysis::EdcGroup>& groups,
                                   const std::vector<std::vector<double>>& edc_mod_j,
                                   const QString& model_name) {
  edc_plot_->clearPlottables();  // graphs and their error bars
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const bool positive = groups[g].positive_well;
    const QString well = positive ? tr("z\u208a* well") : tr("z\u208b* well");
    QVector<double> f0, measured, error, predicted;
    for (std::size_t i = 0; i < groups[g].levels.size(); ++i) {
      const auto& m = groups[g].levels[i];
      f0.push_back(m.f0_n);
      measured.push_back(1e3 * m.edc_j);
      error.push_back(3e3 * m.edc_std_j);  // ±3σ as the paper's Fig. 10
      if (g < edc_mod_j.size() && i < edc_mod_j[g].size()) {
        predicted.push_back(1e3 * edc_mod_j[g][i]);
      }
    }
    QCPGraph* points = edc_plot_->addGraph();
    points->setName(well + tr(" measured \u00b13\u03c3"));
    points->setData(f0, measured);
    points->setLineStyle(QCPGraph::lsNone);
    points->setPen(
        QPen(well_colour(positive ? analysis::Well::Positive : analysis::Well::Negative)));
    points->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, 6));
    auto* bars = new QCPErrorBars(edc_plot_->xAxis, edc_plot_->yAxis);
    bars->removeFromLegend();
    bars->setDataPlottable(points);
    bars->setData(error);
    bars->setPen(QPen(well_colour(positive ? analysis::Well::Positive : analysis::Well::Negative)));
    if (predicted.size() != f0.size()) continue;  // the measurement alone
    QCPGraph* line = edc_plot_->addGraph();
    line->setName(well + " " + model_name);
    line->setData(f0, predicted);
    QPen pen(well_colour(positive ? analysis::Well::Positive : analysis::Well::Negative), 2,
             Qt::DashLine);
    line->setPen(pen);
  }
  edc_plot_->legend->setVisible(edc_plot_->legend->itemCount() > 0);
  set_plot_hint(edc_plot_, edc_plot_->plottableCount() > 0
                               ? QString()
                               : tr("No stepped-sine level to show in the opened recordings."));
  edc_plot_->rescaleAxes();
  edc_plot_->xAxis->scaleRange(1.08);
  // From 0, with room above the top level's point and error bar so neither sits on the frame.
  const double top_mj = edc_plot_->yAxis->range().upper;
  edc_plot_->yAxis->setRange(0.0, top_mj > 0.0 ? 1.06 * top_mj : 1.0);
  edc_plot_->replot(QCustomPlot::rpQueuedReplot);
}

void IdentificationPanel::with_figure_data(std::function<void()> then, const QString& export_dir) {
  if (!fitted_) {
    status_label_->setText(tr("Fit first: the figures show the last fit."));
    if (!export_dir.isEmpty()) Q_EMIT export_finished(status_label_->text(), false);
    return;
  }
  if (busy()) {
    status_label_->setText(tr("Busy: wait for the running job or cancel it."));
    if (!export_dir.isEmpty()) Q_EMIT export_finished(status_label_->text(), false);
    return;
  }
  if (figure_data_ && export_dir.isEmpty()) {
    then();
    return;
  }
  after_figure_data_ = std::move(then);
  progress_->setRange(0, 0);  // busy indicator: the slices and curves report no fraction
  set_busy(true);
  status_label_->setText(figure_data_
                             ? tr("Writing the results\u2026")
                             : tr("Computing the cost slices and sensitivity curves\u2026"));
  figure_data_job_->start(fitted_, figure_data_, export_dir.toStdString());
}

void IdentificationPanel::on_figure_data_finished(
    std::shared_ptr<const FigureDataOutcome> outcome) {
  progress_->setRange(0, 1000);
  set_busy(false);
  if (outcome->error.empty() && !outcome->cancelled) progress_->setValue(1000);
  const bool exporting = !outcome->export_dir.empty();
  std::function<void()> then = std::move(after_figure_data_);
  after_figure_data_ = nullptr;
  if (!outcome->error.empty()) {
    const QString message = tr("Error: %1").arg(QString::fromStdString(outcome->error));
    status_label_->setText(message);
    if (exporting) Q_EMIT export_finished(message, false);
    return;
  }
  if (outcome->cancelled) {
    status_label_->setText(tr("Cancelled."));
    if (exporting) Q_EMIT export_finished(tr("Cancelled."), false);
    return;
  }
  figure_data_ = outcome->data;
  status_label_->clear();
  if (then) then();
}

void IdentificationPanel::show_figures() {
  with_figure_data([this] {
    std::vector<std::pair<QString, figures::Figure>> tabs;
    for (figures::NamedFigure& f :
         figures::fit_figures(fitted_->fit, *fitted_->objective, *figure_data_)) {
      tabs.emplace_back(figure_tab_name(f.stem), std::move(f.figure));
    }
    if (!figures_dialog_) {
      figures_dialog_ = new FigureDialog(this);
      figures_dialog_->setWindowTitle(tr("Figures of the fit"));
    }
    figures_dialog_->set_figures(tabs);
    figures_dialog_->show();
    figures_dialog_->raise();
    status_label_->setText(tr("Figures of the fit: %1 (Figs. 13\u201316).").arg(tabs.size()));
    Q_EMIT figures_shown();
  });
}

void IdentificationPanel::export_results(const QString& dir) {
  if (!fitted_) {
    with_figure_data({}, dir);  // says why not
    return;
  }
  if (!QDir().mkpath(dir)) {
    const QString message = tr("Error: %1: cannot create the folder").arg(dir);
    status_label_->setText(message);
    Q_EMIT export_finished(message, false);
    return;
  }
  // The worker writes fit.json, the tables and the figures (PNG, drawn without the GUI's plots).
  with_figure_data(
      [this, dir] {
        const QString message = tr("Results written to %1: fit.json, the figures (PNG) and their "
                                   "tables (CSV).")
                                    .arg(dir);
        status_label_->setText(message);
        Q_EMIT export_finished(message, true);
      },
      dir);
}

ResponseDialog* IdentificationPanel::open_branch_dialog() { return open_response_dialog(false); }
ResponseDialog* IdentificationPanel::open_map_dialog() { return open_response_dialog(true); }

ResponseDialog* IdentificationPanel::open_response_dialog(bool map) {
  if (!fitted_) {
    status_label_->setText(tr("Fit first: the branches and the map are of the fitted model."));
    return nullptr;
  }
  const analysis::EdcObjective& objective = *fitted_->objective;
  ResponseDialog::Setup setup;
  try {
    setup.model =
        std::make_shared<const analysis::Model>(objective.form().build(fitted_->fit.theta));
  } catch (const InputError& error) {
    status_label_->setText(tr("Error: %1").arg(QString::fromStdString(error.what())));
    return nullptr;
  }
  double largest_f0_n = 0.0;
  for (const analysis::EdcGroup& group : objective.data().groups) {
    setup.wells.push_back({group.positive_well, group.freq_hz});
    for (const analysis::MeasuredLevel& level : group.levels) {
      largest_f0_n = std::max(largest_f0_n, level.f0_n);
    }
  }
  // The paper's range (Fig. 11: 0.1 to 3.7 N), wider when the test went further.
  setup.start_n = 0.1;
  setup.end_n = std::max(3.7, 1.25 * largest_f0_n);
  setup.harmonics = objective.settings().hbm.harmonics;
  setup.model_name = tr("fitted model").toStdString();
  auto* dialog = new ResponseDialog(map ? ResponseDialog::Kind::Map : ResponseDialog::Kind::Branch,
                                    std::move(setup), this);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  dialog->show();
  dialog->start();
  return dialog;
}

}  // namespace oscilab::ui
