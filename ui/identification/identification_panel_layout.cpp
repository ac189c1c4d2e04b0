// The identification panel's widgets, its jobs' connections and its layout (the constructor);
// what the panel does with them is identification_panel.cpp.
#include <QFileDialog>
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

#include "ui/flow_layout.h"
#include "ui/identification/diagnosis_job.h"
#include "ui/identification/diagnosis_view.h"
#include "ui/identification/figure_data_job.h"
#include "ui/identification/fit_settings_form.h"
#include "ui/identification/identification_panel.h"
#include "ui/plots/plot_helpers.h"
#include "ui/plots/well_colours.h"

namespace oscilab::ui {

IdentificationPanel::IdentificationPanel(QWidget* parent) : QWidget(parent) {
  connect_jobs();
  QGroupBox* records = make_records_group();
  settings_form_ = new FitSettingsForm;
  FlowLayout* buttons = make_buttons();
  make_results();

  // The set-up (recordings and settings) above the results, in a splitter: on a short screen the
  // set-up scrolls and the results keep most of the height; the user moves the divider.
  setup_ = new QWidget;
  auto* setup_layout = new QVBoxLayout(setup_);
  setup_layout->setContentsMargins(0, 0, 0, 0);
  setup_layout->addWidget(records);
  setup_layout->addWidget(settings_form_);
  setup_layout->addStretch(1);
  auto* setup_scroll = new QScrollArea;
  setup_scroll->setObjectName("fit_setup");
  setup_scroll->setWidget(setup_);
  setup_scroll->setWidgetResizable(true);
  setup_scroll->setFrameShape(QFrame::NoFrame);
  setup_scroll->setMinimumHeight(80);
  auto* results = new QWidget;
  auto* results_layout = new QVBoxLayout(results);
  results_layout->setContentsMargins(0, 0, 0, 0);
  results_layout->addLayout(buttons);
  results_layout->addWidget(progress_);
  results_layout->addWidget(status_label_);
  results_layout->addWidget(tabs_, 1);
  splitter_ = new QSplitter(Qt::Vertical);
  splitter_->setObjectName("fit_splitter");
  splitter_->addWidget(setup_scroll);
  splitter_->addWidget(results);
  splitter_->setChildrenCollapsible(false);
  splitter_->setStretchFactor(0, 0);
  splitter_->setStretchFactor(1, 1);
  connect(splitter_, &QSplitter::splitterMoved, this, [this] { splitter_placed_ = true; });
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(splitter_);
  update_result_buttons();
}

// The fit, diagnosis and figure jobs, their progress and results wired to the panel.
void IdentificationPanel::connect_jobs() {
  const auto show_progress = [this](double f) { progress_->setValue(static_cast<int>(1000 * f)); };
  fit_job_ = new FitJob(this);
  connect(fit_job_, &FitJob::progress, this, show_progress);
  connect(fit_job_, &FitJob::convergence_point, this, &IdentificationPanel::add_convergence_point);
  // Still on the worker thread; drawn on the UI thread through the queued connection below.
  connect(fit_job_, &FitJob::preview, this, &IdentificationPanel::fit_preview,
          Qt::DirectConnection);
  connect(fit_job_, &FitJob::finished, this, &IdentificationPanel::on_fit_finished);
  connect(this, &IdentificationPanel::fit_preview, this, &IdentificationPanel::show_preview,
          Qt::QueuedConnection);
  diagnosis_job_ = new DiagnosisJob(this);
  connect(diagnosis_job_, &DiagnosisJob::progress, this, show_progress);
  connect(diagnosis_job_, &DiagnosisJob::stage, this, [this](const QString& text) {
    progress_->setFormat(text + QStringLiteral(" \u2014 %p%"));
    progress_->setTextVisible(true);
  });
  connect(diagnosis_job_, &DiagnosisJob::finished, this,
          &IdentificationPanel::on_diagnosis_finished);
  figure_data_job_ = new FigureDataJob(this);
  connect(figure_data_job_, &FigureDataJob::finished, this,
          &IdentificationPanel::on_figure_data_finished);
}

// The recordings to fit: a list with Add and Remove.
QGroupBox* IdentificationPanel::make_records_group() {
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
  return records;
}

// The job buttons (Fit, Diagnose, Cancel), then the result buttons (figures, export, HBM branch,
// bifurcation map), in rows that wrap with the panel's width.
FlowLayout* IdentificationPanel::make_buttons() {
  fit_button_ = new QPushButton(tr("Fit"));
  fit_button_->setToolTip(tr("Identify the friction parameters from the EDCs (§4, §5)"));
  diagnose_button_ = new QPushButton(tr("Diagnose"));
  diagnose_button_->setToolTip(tr("Find the missing physical effect, add it, refit (or say none)"));
  cancel_button_ = new QPushButton(tr("Cancel"));
  cancel_button_->setEnabled(false);
  connect(fit_button_, &QPushButton::clicked, this, &IdentificationPanel::start_fit);
  connect(diagnose_button_, &QPushButton::clicked, this, &IdentificationPanel::start_diagnosis);
  connect(cancel_button_, &QPushButton::clicked, this, &IdentificationPanel::cancel);
  // The job buttons, then the result buttons, in rows that wrap with the panel's width.
  auto* buttons = new FlowLayout(nullptr, 6, 4);
  buttons->addWidget(fit_button_);
  buttons->addWidget(diagnose_button_);
  buttons->addWidget(cancel_button_);

  figures_button_ = new QPushButton(tr("Figures\u2026"));
  figures_button_->setToolTip(
      tr("Figs. 13\u201316 of the last fit: cost slices, convergence, "
         "EDC, sensitivity, f_d(z)"));
  export_button_ = new QPushButton(tr("Export results\u2026"));
  export_button_->setToolTip(
      tr("Write the FIT JSON (as oscilab-cli fit), the figures (PNG) and their data (CSV) into a "
         "folder"));
  branch_button_ = new QPushButton(tr("HBM branch\u2026"));
  branch_button_->setToolTip(
      tr("Harmonic-balance branches of the fitted model in f0 at the test "
         "frequency, one per well, with stability and folds (Fig. 11)"));
  map_button_ = new QPushButton(tr("Bifurcation map\u2026"));
  map_button_->setToolTip(
      tr("Bifurcation map of the fitted model by time simulation, over its HBM branches "
         "(Fig. 17)"));
  connect(figures_button_, &QPushButton::clicked, this, &IdentificationPanel::show_figures);
  connect(export_button_, &QPushButton::clicked, this, [this] {
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Export results into"));
    if (!dir.isEmpty()) export_results(dir);
  });
  connect(branch_button_, &QPushButton::clicked, this, [this] { open_branch_dialog(); });
  connect(map_button_, &QPushButton::clicked, this, [this] { open_map_dialog(); });
  buttons->addWidget(figures_button_);
  buttons->addWidget(export_button_);
  buttons->addWidget(branch_button_);
  buttons->addWidget(map_button_);
  return buttons;
}

// The progress bar, the status line and the result tabs (EDC, parameters, convergence and the
// diagnosis's pages).
void IdentificationPanel::make_results() {
  progress_ = new QProgressBar;
  progress_->setObjectName("job_progress");
  progress_->setRange(0, 1000);
  progress_->setTextVisible(false);
  progress_->hide();  // shown while a job runs: its height goes to the results otherwise
  status_label_ = new QLabel(tr("Add the recordings of both wells, then Fit or Diagnose."));
  status_label_->setWordWrap(true);
  parameter_table_ = new QTableWidget(0, 5);
  parameter_table_->setHorizontalHeaderLabels(
      {tr("parameter"), tr("value"), tr("std error"), tr("95 % interval"), tr("note")});
  parameter_table_->horizontalHeader()->setStretchLastSection(true);
  parameter_table_->verticalHeader()->hide();
  edc_plot_ = new QCustomPlot;
  edc_plot_->setMinimumHeight(260);
  edc_plot_->xAxis->setLabel(tr("forcing amplitude f0 [N]"));
  edc_plot_->yAxis->setLabel(tr("EDC [mJ]"));
  edc_plot_->legend->setVisible(false);  // until something is drawn
  set_plot_hint(edc_plot_, tr("The measured EDC appears once the recordings are analysed."));
  edc_plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignTop | Qt::AlignLeft);
  convergence_plot_ = new QCustomPlot;
  convergence_plot_->xAxis->setLabel(tr("model evaluations"));
  convergence_plot_->yAxis->setLabel(tr("best \u03c7\u00b2 (log scale)"));
  convergence_plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
  convergence_plot_->yAxis->setTicker(QSharedPointer<QCPAxisTickerLog>::create());
  convergence_plot_->addGraph()->setPen(QPen(well_colour(analysis::Well::Positive), 2));

  diagnosis_view_ = new DiagnosisView;
  tabs_ = new QTabWidget;
  tabs_->addTab(edc_plot_, tr("EDC"));
  tabs_->addTab(parameter_table_, tr("Parameters"));
  tabs_->addTab(convergence_plot_, tr("Convergence"));
  tabs_->addTab(diagnosis_view_, tr("Diagnosis"));
  tabs_->addTab(diagnosis_view_->residual_page(), tr("Residuals"));
  tabs_->addTab(diagnosis_view_->missing_energy_page(), tr("Missing energy"));
  tabs_->addTab(diagnosis_view_->budget_page(), tr("\u03c3 budget"));

  // Seven tabs in a panel a third of a laptop screen wide: no scroll arrows to hide the last
  // ones; a tab too narrow for its name elides it and says it in full on hover.
  tabs_->setUsesScrollButtons(false);
  tabs_->setElideMode(Qt::ElideRight);
  tabs_->tabBar()->setStyleSheet(QStringLiteral("QTabBar::tab { padding: 4px 7px; }"));
  for (int i = 0; i < tabs_->count(); ++i) tabs_->setTabToolTip(i, tabs_->tabText(i));
}

}  // namespace oscilab::ui
