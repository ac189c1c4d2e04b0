#include "ui/live/adaptive_test_panel.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QStandardPaths>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "analysis/identification/fit_setup.h"
#include "analysis/model/model_json.h"
#include "ui/number_box.h"
#include "ui/number_text.h"
#include "ui/plots/plot_helpers.h"
#include "ui/plots/plot_theme.h"
#include "ui/qt_text.h"

namespace oscilab::ui {
namespace {

// Okabe–Ito's colour-blind-safe palette (black last); past eight, the colours again dashed.
const QColor kHypothesisColours[] = {{0, 114, 178}, {213, 94, 0},   {0, 158, 115},  {204, 121, 167},
                                     {230, 159, 0}, {86, 180, 233}, {240, 228, 66}, {0, 0, 0}};
constexpr int kColours = static_cast<int>(std::size(kHypothesisColours));

QPen hypothesis_pen(int index) {
  QPen pen(kHypothesisColours[index % kColours], index == 0 ? 2.5 : 1.6);
  if (index >= kColours) pen.setStyle(Qt::DashLine);
  return pen;
}

QString well_name(bool positive) {
  return positive ? QObject::tr("positive") : QObject::tr("negative");
}

// A line edit with a "…" button beside it that opens `choose`.
QWidget* with_browse_button(QLineEdit* edit, const std::function<void()>& choose) {
  auto* row = new QWidget;
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(2);
  layout->addWidget(edit, 1);
  auto* browse = new QToolButton;
  browse->setText(QStringLiteral("…"));
  QObject::connect(browse, &QToolButton::clicked, edit, choose);
  layout->addWidget(browse);
  return row;
}

}  // namespace

AdaptiveTestPanel::AdaptiveTestPanel(QWidget* parent) : QWidget(parent) {
  job_ = new AdaptiveTestJob(this);
  connect(job_, &AdaptiveTestJob::decided, this, &AdaptiveTestPanel::show_step);
  connect(job_, &AdaptiveTestJob::awaiting_changed, this, &AdaptiveTestPanel::set_awaiting);
  connect(job_, &AdaptiveTestJob::progress, this,
          [this](double f) { progress_->setValue(static_cast<int>(std::lround(f * 1000.0))); });
  connect(job_, &AdaptiveTestJob::finished, this,
          [this](const std::shared_ptr<const AdaptiveTestOutcome>& outcome) {
            show_outcome(*outcome);
            update_buttons();
            Q_EMIT test_finished();
          });

  // The strip chart of the weights and the table of the weights now.
  plot_ = new QCustomPlot;
  plot_->setMinimumSize(200, 180);
  add_plot_title(plot_, tr("Model weights over the test"));
  frame_axes(plot_, tr("shaker time (s)"), tr("weight (BIC)"));
  plot_->yAxis->setRange(-0.02, 1.02);
  plot_->xAxis->setRange(0.0, 100.0);
  set_plot_hint(plot_, tr("Press Start: the pilot in each well, then one level at a time"));

  table_ = new QTableWidget(0, 3);
  table_->setHorizontalHeaderLabels({tr("hypothesis"), tr("weight"), tr("χ²/ν")});
  table_->verticalHeader()->hide();
  table_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  table_->horizontalHeader()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setSectionResizeMode(2, QHeaderView::ResizeToContents);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->setMaximumWidth(330);
  table_->setMinimumHeight(90);

  // The settings over the table of the weights now, beside the strip chart.
  auto* column = new QVBoxLayout;
  column->setContentsMargins(0, 0, 0, 0);
  column->addWidget(make_settings());
  column->addWidget(table_, 1);
  auto* top = new QHBoxLayout;
  top->setContentsMargins(0, 0, 0, 0);
  top->addLayout(column);
  top->addWidget(plot_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addLayout(top, 1);
  layout->addWidget(make_state());
  update_buttons();
}

AdaptiveTestPanel::~AdaptiveTestPanel() = default;  // the job (a child) cancels and joins

QWidget* AdaptiveTestPanel::make_settings() {
  auto* group = new QGroupBox(tr("Adaptive test on the virtual rig"));
  auto* form = new QFormLayout(group);
  form->setContentsMargins(6, 4, 6, 4);
  form->setVerticalSpacing(3);

  rig_truth_ = new QLineEdit(QStringLiteral("paper"));
  rig_truth_->setToolTip(
      tr("What the rig simulates: paper (the paper's model) or a model JSON, for example one with "
         "an effect hidden in it. The test does not see it: it identifies the stiffness from its "
         "own records and weighs the candidate effects."));
  form->addRow(tr("Rig truth"), with_browse_button(rig_truth_, [this] {
                 const QString file = QFileDialog::getOpenFileName(
                     this, tr("The rig's model"), QString(), tr("Model JSON (*.json)"));
                 if (!file.isEmpty()) rig_truth_->setText(file);
               }));
  wells_ = new QComboBox;
  wells_->addItems({tr("both"), tr("positive"), tr("negative")});
  form->addRow(tr("Wells"), wells_);
  f0_min_ = number_box(0.05, 20.0, 0.2, 2, 0.1, tr(" N"));
  f0_max_ = number_box(0.05, 20.0, 2.7, 2, 0.1, tr(" N"));
  auto* f0_row = new QWidget;
  auto* f0_layout = new QHBoxLayout(f0_row);
  f0_layout->setContentsMargins(0, 0, 0, 0);
  f0_layout->addWidget(f0_min_);
  f0_layout->addWidget(new QLabel(tr("to")));
  f0_layout->addWidget(f0_max_);
  form->addRow(tr("f₀"), f0_row);
  freq_ = number_box(0.5, 200.0, 9.0, 2, 0.25, tr(" Hz"));
  form->addRow(tr("Frequency"), freq_);
  budget_ = number_box(10.0, 100000.0, 520.0, 0, 10.0, tr(" s"));
  budget_->setToolTip(tr("Shaker time after which the test stops if no leader is clear"));
  form->addRow(tr("Budget"), budget_);
  effects_ = new QLineEdit;
  effects_->setPlaceholderText(tr("every effect of the vocabulary"));
  effects_->setToolTip(tr("Candidate effects weighed, comma-separated (docs/diagnosis.md)"));
  form->addRow(tr("Effects"), effects_);
  const QString documents = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
  folder_ = new QLineEdit(QDir(documents.isEmpty() ? QDir::homePath() : documents)
                              .filePath(QStringLiteral("oscilab-adaptive-test")));
  folder_->setToolTip(tr("recordings/, decisions.jsonl, report.json and final_model.json"));
  form->addRow(tr("Folder"), with_browse_button(folder_, [this] {
                 const QString dir = QFileDialog::getExistingDirectory(this, tr("Output folder"));
                 if (!dir.isEmpty()) folder_->setText(dir);
               }));
  auto_ = new QCheckBox(tr("Auto: run every proposal"));
  auto_->setChecked(true);
  connect(auto_, &QCheckBox::toggled, this, [this](bool on) {
    job_->set_auto(on);
    update_buttons();
  });
  form->addRow(auto_);
  start_ = new QPushButton(tr("Start"));
  cancel_ = new QPushButton(tr("Cancel"));
  connect(start_, &QPushButton::clicked, this, [this] { start(); });
  start_->setObjectName(QStringLiteral("adaptive_start"));
  connect(cancel_, &QPushButton::clicked, this, &AdaptiveTestPanel::cancel);
  auto* buttons = new QWidget;
  auto* buttons_layout = new QHBoxLayout(buttons);
  buttons_layout->setContentsMargins(0, 0, 0, 0);
  buttons_layout->addWidget(start_);
  buttons_layout->addWidget(cancel_);
  form->addRow(buttons);
  progress_ = new QProgressBar;
  progress_->setRange(0, 1000);
  progress_->setTextVisible(false);
  progress_->setMaximumHeight(8);
  form->addRow(progress_);
  group->setMaximumWidth(330);
  return group;
}

QWidget* AdaptiveTestPanel::make_state() {
  auto* group = new QGroupBox(tr("Decision"));
  auto* layout = new QVBoxLayout(group);
  layout->setContentsMargins(6, 2, 6, 4);
  layout->setSpacing(2);
  const auto line = [&](const QString& name) {
    auto* label = new QLabel;
    label->setObjectName(name);
    label->setWordWrap(true);
    label->setTextInteractionFlags(Qt::TextSelectableByMouse);
    label->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    layout->addWidget(label);
    return label;
  };
  leader_ = line(QStringLiteral("adaptive_leader"));
  stop_rule_ = line(QStringLiteral("adaptive_stop_rule"));
  auto* next_row = new QHBoxLayout;
  proposal_ = new QLabel;
  proposal_->setObjectName(QStringLiteral("adaptive_proposal"));
  proposal_->setWordWrap(true);
  proposal_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  proposal_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
  next_row->addWidget(proposal_, 1);
  run_ = new QPushButton(tr("Run it"));
  skip_ = new QPushButton(tr("Skip"));
  stop_ = new QPushButton(tr("Stop here"));
  run_->setToolTip(tr("Run the proposed level"));
  skip_->setToolTip(tr("Never this setting: propose the next best"));
  stop_->setToolTip(tr("End the test now, then the final diagnosis of what was measured"));
  connect(run_, &QPushButton::clicked, this,
          [this] { job_->answer(analysis::ProposalAnswer::Run); });
  connect(skip_, &QPushButton::clicked, this,
          [this] { job_->answer(analysis::ProposalAnswer::Skip); });
  connect(stop_, &QPushButton::clicked, this,
          [this] { job_->answer(analysis::ProposalAnswer::Stop); });
  for (QPushButton* b : {run_, skip_, stop_}) next_row->addWidget(b, 0, Qt::AlignTop);
  layout->addLayout(next_row);
  verdict_ = line(QStringLiteral("adaptive_verdict"));
  leader_->setText(tr("Leader: none yet."));
  stop_rule_->setText(
      tr("Stop rule: a leader with weight ≥ 0.99 whose misfit is at the noise, "
         "or nothing left to tell apart, or the budget spent."));
  proposal_->setText(tr("Next: proposed after the pilot."));
  return group;
}

AdaptiveTestJob::Request AdaptiveTestPanel::request() const {
  AdaptiveTestJob::Request r{analysis::model_from_spec(rig_truth_->text().trimmed().toStdString()),
                             {},
                             1,
                             {},
                             folder_->text().trimmed().toStdString(),
                             auto_->isChecked()};
  if (r.folder.empty()) throw InputError("Folder: give the folder the test writes into");
  analysis::AdaptiveTestOptions& o = r.options;
  o.settings.f0_min_n = f0_min_->value();
  o.settings.f0_max_n = f0_max_->value();
  o.settings.freq_hz = freq_->value();
  o.settings.positive_well = wells_->currentIndex() != 2;
  o.settings.negative_well = wells_->currentIndex() != 1;
  o.stop.budget_s = budget_->value();
  o.setup.stiffness = analysis::parse_stiffness_source("identified", "stiffness");
  for (const QString& effect : effects_->text().split(',', Qt::SkipEmptyParts)) {
    o.hypotheses.effects.push_back(effect.trimmed().toStdString());
  }
  // The schedule the settings book: each level's dwell and each run's lead-in.
  r.schedule.hold_s = o.settings.dwell_s;
  r.schedule.lead_in_s = o.settings.settling_s;
  analysis::validate_as_named(o, {{"settings.f0_range_n", "f₀"},
                                  {"settings.freq_hz", "Frequency"},
                                  {"settings.wells", "Wells"},
                                  {"stop.budget_s", "Budget"},
                                  {"hypotheses.effects", "Effects"}});
  return r;
}

bool AdaptiveTestPanel::start() {
  if (job_->running()) return false;
  AdaptiveTestJob::Request r;
  try {
    r = request();
  } catch (const InputError& error) {
    verdict_->setText(tr("Not started: %1").arg(qtext(error.what())));
    return false;
  }
  return start(std::move(r));
}

bool AdaptiveTestPanel::start(AdaptiveTestJob::Request r) {
  if (job_->running()) return false;
  steps_.clear();
  awaiting_ = false;
  budget_s_ = r.options.stop.budget_s;
  table_->setRowCount(0);
  plot_->clearGraphs();
  set_plot_hint(plot_, tr("The pilot runs in each well; the first weights follow its fits"));
  plot_->replot();
  leader_->setText(tr("Leader: none yet."));
  proposal_->setText(tr("Next: proposed after the pilot."));
  verdict_->setText(tr("Running: the pilot sweep in each well, then every hypothesis fitted."));
  progress_->setValue(0);
  job_->start(std::move(r));
  update_buttons();
  return true;
}

void AdaptiveTestPanel::cancel() {
  job_->cancel();
  verdict_->setText(tr("Cancelling…"));
}

bool AdaptiveTestPanel::running() const { return job_->running(); }

void AdaptiveTestPanel::set_awaiting(bool awaiting) {
  awaiting_ = awaiting;
  if (awaiting) {
    verdict_->setText(
        tr("Waiting for you: Run it, Skip (the next best is proposed) or Stop "
           "here; or tick Auto."));
  }
  update_buttons();
}

void AdaptiveTestPanel::update_buttons() {
  const bool running = job_->running();
  start_->setEnabled(!running);
  cancel_->setEnabled(running);
  for (QPushButton* b : {run_, skip_, stop_}) b->setEnabled(running && awaiting_);
  for (QWidget* w : std::initializer_list<QWidget*>{rig_truth_, wells_, f0_min_, f0_max_, freq_,
                                                    budget_, effects_, folder_}) {
    w->setEnabled(!running);
  }
}

void AdaptiveTestPanel::show_step(const AdaptiveTestStep& step) {
  steps_.push_back(step);
  redraw_weights();
  const analysis::StopDecision& d = step.decision;
  const int leader = d.leader;
  if (leader >= 0 && leader < static_cast<int>(step.labels.size())) {
    const QString misfit = std::isfinite(d.noise_reduced_chi2)
                               ? tr("χ²/ν %1 against the noise level %2 (%3)")
                                     .arg(qtext(number_text("%.3g", d.reduced_chi2)))
                                     .arg(qtext(number_text("%.3g", d.noise_reduced_chi2)))
                                     .arg(d.gap_at_noise ? tr("at the noise") : tr("above it"))
                               : tr("its misfit not judged yet (no more levels than parameters)");
    leader_->setText(tr("Leader: <b>%1</b>, weight %2; %3; %4 levels, %5 s of shaker time.")
                         .arg(qtext(step.labels[static_cast<std::size_t>(leader)]))
                         .arg(qtext(number_text("%.4f", d.leader_weight)))
                         .arg(misfit)
                         .arg(step.levels)
                         .arg(qtext(number_text("%.1f", step.shaker_time_s))));
  } else {
    leader_->setText(tr("Leader: none solved yet."));
  }
  stop_rule_->setText(
      (d.stop ? tr("Stop: %1") : tr("Stop rule: not yet: %1")).arg(qtext(d.reason)));
  if (step.proposed) {
    const analysis::SettingScore& p = step.proposal;
    proposal_->setText(tr("Next: <b>%1 N, %2 Hz, %3 well</b>: %4 (update %5 s)")
                           .arg(qtext(number_text("%.2f", p.f0_n)))
                           .arg(qtext(number_text("%.2f", p.freq_hz)))
                           .arg(well_name(p.positive_well))
                           .arg(qtext(step.proposal_reason).toHtmlEscaped())
                           .arg(qtext(number_text("%.2f", step.update_s))));
  } else {
    proposal_->setText(
        tr("Next: none: the test stops; the final diagnosis of every recording "
           "follows."));
  }
  verdict_->setText(tr("Running: decision %1 at %2 s of shaker time (budget %3 s).")
                        .arg(step.index + 1)
                        .arg(qtext(number_text("%.1f", step.shaker_time_s)))
                        .arg(qtext(number_text("%.0f", budget_s_))));
}

void AdaptiveTestPanel::redraw_weights() {
  if (steps_.empty()) return;
  const AdaptiveTestStep& last = steps_.back();
  const int n = static_cast<int>(last.labels.size());
  while (plot_->graphCount() < n) {
    QCPGraph* graph = plot_->addGraph();
    graph->setPen(hypothesis_pen(plot_->graphCount() - 1));
    graph->setLineStyle(QCPGraph::lsStepLeft);
    graph->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssDisc, 4.0));
  }
  double t_max = 0.0;
  for (int h = 0; h < n; ++h) {
    QVector<double> t, w;
    for (const AdaptiveTestStep& step : steps_) {
      if (static_cast<int>(step.weights.size()) <= h) continue;
      t.push_back(step.shaker_time_s);
      w.push_back(step.weights[static_cast<std::size_t>(h)]);
      t_max = std::max(t_max, step.shaker_time_s);
    }
    plot_->graph(h)->setData(t, w, true);
    plot_->graph(h)->setName(qtext(last.labels[static_cast<std::size_t>(h)]));
  }
  plot_->xAxis->setRange(0.0, std::max(60.0, t_max * 1.08));
  set_plot_hint(plot_, {});
  plot_->replot();

  // The table, the leader first.
  std::vector<int> order(static_cast<std::size_t>(n));
  for (int h = 0; h < n; ++h) order[static_cast<std::size_t>(h)] = h;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return last.weights[static_cast<std::size_t>(a)] > last.weights[static_cast<std::size_t>(b)];
  });
  table_->setRowCount(n);
  for (int row = 0; row < n; ++row) {
    const auto h = static_cast<std::size_t>(order[static_cast<std::size_t>(row)]);
    auto* name = new QTableWidgetItem(qtext(last.labels[h]));
    QPixmap swatch(12, 12);
    swatch.fill(hypothesis_pen(static_cast<int>(h)).color());
    name->setIcon(QIcon(swatch));
    name->setToolTip(qtext(last.labels[h]));
    table_->setItem(row, 0, name);
    table_->setItem(row, 1, new QTableWidgetItem(qtext(number_text("%.4f", last.weights[h]))));
    const double chi2 = last.reduced_chi2[h];
    table_->setItem(
        row, 2,
        new QTableWidgetItem(std::isfinite(chi2) ? qtext(number_text("%.3g", chi2)) : tr("—")));
  }
}

void AdaptiveTestPanel::show_outcome(const AdaptiveTestOutcome& outcome) {
  awaiting_ = false;
  const QString folder = qtext(outcome.folder);
  if (!outcome.error.empty()) {
    verdict_->setText(tr("Failed: %1").arg(qtext(outcome.error)));
    return;
  }
  const analysis::AdaptiveTestResult& r = outcome.result;
  if (outcome.cancelled || r.status == JobStatus::Cancelled) {
    verdict_->setText(tr("Cancelled after %1 s of shaker time; the recordings and decisions so "
                         "far are in %2.")
                          .arg(qtext(number_text("%.1f", r.shaker_time_s)))
                          .arg(folder));
    return;
  }
  QString text = tr("Done: %1 levels (%2 adaptive), %3 s of shaker time. ")
                     .arg(r.levels)
                     .arg(r.adaptive_levels)
                     .arg(qtext(number_text("%.1f", r.shaker_time_s)));
  if (r.diagnosed) {
    text += tr("Verdict of the final diagnosis: <b>%1</b>%2. ")
                .arg(qtext(r.diagnosis.verdict))
                .arg(r.leader() == r.diagnosis.verdict
                         ? tr(", as the test's leader")
                         : tr(" (the test's leader: %1)").arg(qtext(r.leader())));
  } else {
    text += tr("Leader: <b>%1</b>. ").arg(qtext(r.leader()));
  }
  text += tr("Written to %1.").arg(folder);
  verdict_->setText(text);
}

}  // namespace oscilab::ui
