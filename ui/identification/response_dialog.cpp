#include "ui/identification/response_dialog.h"

#include <algorithm>
#include <cstdio>
#include <exception>

#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSpinBox>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "analysis/figures/hbm_figures.h"
#include "ui/identification/bifurcation_map_job.h"
#include "ui/identification/branch_job.h"
#include "ui/identification/figure_renderer.h"
#include "ui/number_box.h"
#include "ui/plots/plot_context_menu.h"

namespace oscilab::ui {

namespace {

// UTF-8, as the figures take their text.
const char* well_label(bool positive) { return positive ? "z\u208a* well" : "z\u208b* well"; }

QSpinBox* count_box(int low, int high, int value) {
  auto* box = new QSpinBox;
  box->setRange(low, high);
  box->setValue(value);
  return box;
}

}  // namespace

ResponseDialog::ResponseDialog(Kind kind, Setup setup, QWidget* parent)
    : QDialog(parent), kind_(kind), setup_(std::move(setup)) {
  setWindowTitle(
      kind_ == Kind::Branch
          ? tr("HBM branches of the %1").arg(QString::fromStdString(setup_.model_name))
          : tr("Bifurcation map of the %1").arg(QString::fromStdString(setup_.model_name)));
  const auto show_progress = [this](double f) { progress_->setValue(static_cast<int>(1000 * f)); };
  if (kind_ == Kind::Branch) {
    branch_job_ = new BranchJob(this);
    connect(branch_job_, &BranchJob::progress, this, show_progress);
    connect(branch_job_, &BranchJob::finished, this,
            [this](std::shared_ptr<const BranchOutcome> outcome) {
              show_outcome(outcome->error, outcome->cancelled, outcome->branches, {});
            });
  } else {
    map_job_ = new BifurcationMapJob(this);
    connect(map_job_, &BifurcationMapJob::progress, this, show_progress);
    connect(map_job_, &BifurcationMapJob::finished, this,
            [this](std::shared_ptr<const BifurcationMapOutcome> outcome) {
              show_outcome(outcome->error, outcome->cancelled, outcome->branches, outcome->map);
            });
  }

  start_box_ = number_box(0.0, 1000.0, setup_.start_n, 3, 0.1, tr(" N"));
  end_box_ = number_box(0.001, 1000.0, setup_.end_n, 3, 0.1, tr(" N"));
  harmonics_box_ = count_box(1, 200, setup_.harmonics);
  max_step_box_ = number_box(1e-4, 10.0, 0.1, 4, 0.01, QString());
  max_step_box_->setToolTip(
      tr("Largest step in scaled arc length (docs/hbm.md); folds are "
         "resolved by the turning-angle limit"));
  auto* settings = new QFormLayout;
  auto* range = new QHBoxLayout;
  range->addWidget(start_box_);
  range->addWidget(new QLabel(tr("to")));
  range->addWidget(end_box_);
  settings->addRow(tr("Forcing amplitude f0"), range);
  settings->addRow(tr("Harmonics H"), harmonics_box_);
  settings->addRow(tr("Largest arc-length step"), max_step_box_);
  auto* map_settings = new QFormLayout;  // beside the HBM settings, to leave the plot room
  if (kind_ == Kind::Map) {
    const analysis::BifurcationMapOptions defaults;
    map_step_box_ = number_box(0.001, 100.0, defaults.step_n, 3, 0.01, tr(" N"));
    hold_box_ = count_box(2, 1000000, defaults.hold_periods);
    hold_box_->setToolTip(tr("Forcing periods simulated at each level (ramp included)"));
    sampled_box_ = count_box(1, 1000000, defaults.sampled_periods);
    sampled_box_->setToolTip(tr("Last periods of each level whose z(nT) is plotted"));
    map_settings->addRow(tr("Map: level step"), map_step_box_);
    map_settings->addRow(tr("Map: periods per level"), hold_box_);
    map_settings->addRow(tr("Map: periods sampled"), sampled_box_);
  }

  compute_button_ = new QPushButton(tr("Compute"));
  cancel_button_ = new QPushButton(tr("Cancel"));
  export_button_ = new QPushButton(tr("Export CSV\u2026"));
  figure_button_ = new QPushButton(tr("Export figure\u2026"));
  auto* close_button = new QPushButton(tr("Close"));
  connect(compute_button_, &QPushButton::clicked, this, &ResponseDialog::start);
  connect(cancel_button_, &QPushButton::clicked, this, &ResponseDialog::cancel);
  connect(close_button, &QPushButton::clicked, this, &QDialog::close);
  connect(export_button_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getSaveFileName(
        this, tr("Export CSV"), kind_ == Kind::Branch ? "branches.csv" : "map.csv",
        tr("CSV (*.csv)"));
    if (!path.isEmpty() && !export_csv(path)) {
      QMessageBox::warning(this, tr("Export CSV"), status_label_->text());
    }
  });
  connect(figure_button_, &QPushButton::clicked, this,
          [this] { export_plot_interactively(*plot_, this); });
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(compute_button_);
  buttons->addWidget(cancel_button_);
  buttons->addStretch(1);
  buttons->addWidget(export_button_);
  buttons->addWidget(figure_button_);
  buttons->addWidget(close_button);

  progress_ = new QProgressBar;
  progress_->setRange(0, 1000);
  progress_->setTextVisible(false);
  status_label_ = new QLabel;
  status_label_->setWordWrap(true);
  plot_ = new QCustomPlot;
  // Panels of at least ~280 px (the map has three, the branches two), so that the longest axis
  // label (the amplitude's, ~280 px at 10 pt) fits; a smaller window scrolls.
  plot_->setMinimumSize(600, kind_ == Kind::Branch ? 580 : 3 * 300);
  auto* scroll = new QScrollArea;
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setWidget(plot_);

  auto* top = new QHBoxLayout;
  top->addLayout(settings);
  top->addSpacing(24);
  top->addLayout(map_settings);
  top->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top);
  layout->addLayout(buttons);
  layout->addWidget(progress_);
  layout->addWidget(status_label_);
  layout->addWidget(scroll, 1);
  resize(1000, kind_ == Kind::Branch ? 820 : 1000);
  set_busy(false);
}

// The workers must end before the dialog goes (the jobs' destructors cancel and join).
ResponseDialog::~ResponseDialog() {
  delete branch_job_;
  delete map_job_;
}

void ResponseDialog::set_f0_range(double start_n, double end_n) {
  start_box_->setValue(start_n);
  end_box_->setValue(end_n);
}

void ResponseDialog::set_harmonics(int harmonics) { harmonics_box_->setValue(harmonics); }

void ResponseDialog::set_map_settings(double step_n, int hold_periods, int sampled_periods) {
  if (kind_ != Kind::Map) return;
  map_step_box_->setValue(step_n);
  hold_box_->setValue(hold_periods);
  sampled_box_->setValue(sampled_periods);
}

// As `oscilab-cli hbm --f0 A:B --freq F --harmonics H --max-step S`.
analysis::ContinuationOptions ResponseDialog::continuation_options(const Well& well) const {
  analysis::ContinuationOptions options;
  options.start = start_box_->value();
  options.end = end_box_->value();
  options.freq_hz = well.freq_hz;
  options.positive_well = well.positive;
  options.hbm.harmonics = harmonics_box_->value();
  options.max_step = max_step_box_->value();
  options.initial_step = std::min(options.initial_step, options.max_step);
  return options;
}

// As `oscilab-cli hbm --map … --map-step --map-hold --map-sampled` over the same f0 range.
analysis::BifurcationMapOptions ResponseDialog::map_options() const {
  analysis::BifurcationMapOptions options;
  options.freq_hz = setup_.wells.empty() ? options.freq_hz : setup_.wells.front().freq_hz;
  options.start_n = start_box_->value();
  options.end_n = end_box_->value();
  options.positive_well = options.negative_well = false;
  for (const Well& well : setup_.wells) {
    (well.positive ? options.positive_well : options.negative_well) = true;
  }
  if (kind_ == Kind::Map) {
    options.step_n = map_step_box_->value();
    options.hold_periods = hold_box_->value();
    options.sampled_periods = sampled_box_->value();
  }
  return options;
}

bool ResponseDialog::busy() const {
  return (branch_job_ && branch_job_->running()) || (map_job_ && map_job_->running());
}

void ResponseDialog::set_busy(bool busy) {
  compute_button_->setEnabled(!busy);
  cancel_button_->setEnabled(busy);
  const bool have = !branches_.empty() && (kind_ == Kind::Branch || !map_.rows.empty());
  export_button_->setEnabled(!busy && have);
  figure_button_->setEnabled(!busy && have);
}

void ResponseDialog::cancel() {
  if (branch_job_) branch_job_->cancel();
  if (map_job_) map_job_->cancel();
  status_label_->setText(tr("Cancelling\u2026"));
}

void ResponseDialog::start() {
  if (busy() || !setup_.model) return;
  std::vector<analysis::ContinuationOptions> continuations;
  for (const Well& well : setup_.wells) continuations.push_back(continuation_options(well));
  harmonics_computing_ = harmonics_box_->value();
  progress_->setValue(0);
  if (map_job_) {
    status_label_->setText(tr("Following the branches, then simulating the map\u2026"));
    map_job_->start(setup_.model, std::move(continuations), map_options());
  } else {
    status_label_->setText(tr("Following the branches\u2026"));
    branch_job_->start(setup_.model, std::move(continuations));
  }
  set_busy(true);
}

void ResponseDialog::show_outcome(const std::string& error, bool cancelled,
                                  const std::vector<analysis::Branch>& branches,
                                  const analysis::BifurcationMap& map) {
  QString message;
  if (!error.empty()) {
    message = tr("Error: %1").arg(QString::fromStdString(error));
  } else if (cancelled) {
    message = tr("Cancelled.");
  } else {
    branches_ = branches;
    map_ = map;
    harmonics_shown_ = harmonics_computing_;
    QStringList parts;
    for (const analysis::Branch& b : branches_) {
      QString part = tr("%1: %2 points").arg(well_label(b.positive_well)).arg(b.points.size());
      const auto folds = b.events_of(analysis::PointMarker::Fold).size();
      const auto flips = b.events_of(analysis::PointMarker::PeriodDoubling).size();
      part += (folds == 1 ? tr(", 1 fold") : tr(", %1 folds").arg(folds)) +
              (flips == 1 ? tr(", 1 period doubling") : tr(", %1 period doublings").arg(flips));
      if (b.status != JobStatus::Ok)
        part += tr(" (stopped: %1)").arg(QString::fromStdString(b.message));
      parts << part;
    }
    if (kind_ == Kind::Map) {
      parts << tr("map: %1 levels, %2 sections").arg(map_.levels.size()).arg(map_.rows.size());
      for (bool positive : {true, false}) {
        int previous = 0;
        for (const analysis::BifurcationMapLevel& level : map_.levels_of(positive)) {
          if (level.distinct_points > 1 && previous <= 1) {
            parts << tr("%1: %2 distinct points from f0 = %3 N")
                         .arg(well_label(positive))
                         .arg(level.distinct_points)
                         .arg(level.f0_n, 0, 'g', 4);
          }
          previous = level.distinct_points;
        }
      }
      if (map_.status != JobStatus::Ok) parts << QString::fromStdString(map_.message);
    }
    message = parts.join("; ") + ".";
    draw();
  }
  status_label_->setText(message);
  set_busy(false);
  progress_->setValue(1000);
  Q_EMIT computed(message);
}

std::string ResponseDialog::title() const {
  char text[200];
  std::snprintf(text, sizeof text, "%s, %.4g Hz, H = %d", setup_.model_name.c_str(),
                setup_.wells.empty() ? 0.0 : setup_.wells.front().freq_hz, harmonics_shown_);
  return text;
}

void ResponseDialog::draw() {
  std::vector<figures::NamedBranch> named;
  for (const analysis::Branch& b : branches_) named.push_back({well_label(b.positive_well), &b});
  if (named.empty()) return;
  if (kind_ == Kind::Branch) {
    render_figure(
        *plot_, figures::branch_figure(title() + ": harmonic balance, continuation in f0", named));
  } else {
    const analysis::BifurcationMapOptions& o = map_.options;
    char text[120];
    std::snprintf(text, sizeof text,
                  ": bifurcation map, time simulation stepped %g N, %d periods "
                  "per level",
                  o.step_n, o.hold_periods);
    render_figure(*plot_, figures::map_figure(title() + text, named, map_));
  }
  plot_->replot();
}

bool ResponseDialog::export_csv(const QString& path) {
  try {
    if (branches_.empty() || (kind_ == Kind::Map && map_.rows.empty())) {
      throw InputError(path.toStdString() + ": nothing computed yet to export");
    }
    if (kind_ == Kind::Branch) {
      std::vector<figures::CsvBranch> csv;
      for (const analysis::Branch& b : branches_) {
        csv.push_back({&b, analysis::well_of(b.positive_well), 1});
      }
      figures::write_branches_csv(csv, csv.size() > 1, false, path.toStdString());
    } else {
      analysis::write_bifurcation_map_csv(map_, path.toStdString());
    }
  } catch (const InputError& error) {
    status_label_->setText(tr("Error: %1").arg(QString::fromStdString(error.what())));
    return false;
  }
  status_label_->setText(tr("Written to %1.").arg(path));
  return true;
}

}  // namespace oscilab::ui
