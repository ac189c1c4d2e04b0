#include "ui/identification/diagnosis_view.h"

#include <algorithm>

#include <QHeaderView>
#include <QLabel>
#include <QScrollArea>
#include <QTableWidget>
#include <QVBoxLayout>

#include <qcustomplot.h>

#include "analysis/figures/diagnosis_figures.h"
#include "ui/identification/figure_renderer.h"
#include "ui/table_cells.h"

namespace oscilab::ui {
namespace {

// Each column's header says its name on hover (a narrow panel cuts it).
void add_header_tooltips(QTableWidget* table) {
  for (int c = 0; c < table->columnCount(); ++c) {
    if (QTableWidgetItem* header = table->horizontalHeaderItem(c)) {
      header->setToolTip(header->text().replace('\n', ' '));
    }
  }
}

// Every cell's full text on hover, after its column's name: a column cut by a narrow panel
// still reads in full.
void add_cell_tooltips(QTableWidget* table) {
  for (int r = 0; r < table->rowCount(); ++r) {
    for (int c = 0; c < table->columnCount(); ++c) {
      QTableWidgetItem* item = table->item(r, c);
      const QTableWidgetItem* header = table->horizontalHeaderItem(c);
      if (item && header) {
        item->setToolTip(
            QStringLiteral("%1: %2").arg(header->text().replace('\n', ' '), item->text()));
      }
    }
  }
}

// The verdict's supporting evidence and the response fingerprints before and after, for the
// label under the verdict.
QString verdict_details(const analysis::DiagnosisResult& r) {
  QString out;
  for (const auto& s : r.steps) {
    if (s.effect != r.verdict) continue;
    QString supported;
    for (const auto& e : s.evidence) {
      if (e.supports()) {
        supported += QStringLiteral("%1%2 (\u0394\u03c7\u00b2 %3)")
                         .arg(supported.isEmpty() ? "" : ", ")
                         .arg(QString::fromStdString(e.name))
                         .arg(e.delta_chi2(), 0, 'g', 3);
      }
    }
    out += QObject::tr("<br>Supported by: %1").arg(supported.isEmpty() ? "—" : supported);
  }
  QString fingerprints;
  for (std::size_t i = 0; i < r.baseline_maps.response.items.size(); ++i) {
    const auto& b = r.baseline_maps.response.items[i];
    if (b.levels == 0 || i >= r.final_maps.response.items.size()) continue;
    fingerprints += QStringLiteral("%1%2 %3 \u2192 %4")
                        .arg(fingerprints.isEmpty() ? "" : ", ")
                        .arg(QString::fromStdString(b.name))
                        .arg(b.chi2 / b.levels, 0, 'g', 3)
                        .arg(r.final_maps.response.items[i].chi2 / b.levels, 0, 'g', 3);
  }
  if (!fingerprints.isEmpty()) {
    out += QObject::tr(
               "<br>Response fingerprints, \u03c7\u00b2 per level (baseline \u2192 "
               "final): %1")
               .arg(fingerprints);
  }
  if (r.incomplete) {
    out += QObject::tr("<br><b>Incomplete:</b> %1").arg(QString::fromStdString(r.message));
  }
  return out;
}

// Whether the final model explains the data within its noise, next to the verdict.
QString gap_text(const analysis::DiagnosisResult& r) {
  if (r.gap_explained) {
    return QObject::tr(
               " &nbsp; <span style=\"color:#2e7d32\">gap explained</span> "
               "(χ²/ν %1 ≤ %2)")
        .arg(r.final_maps.reduced_chi2, 0, 'g', 3)
        .arg(r.final_noise_reduced_chi2, 0, 'g', 3);
  }
  return QObject::tr("<br><b><span style=\"color:#c62828\">Gap not explained:</span></b> %1")
      .arg(QString::fromStdString(analysis::gap_open_message(r)).toHtmlEscaped());
}

}  // namespace

DiagnosisView::DiagnosisView(QWidget* parent) : QWidget(parent) {
  verdict_label_ = new QLabel;
  verdict_label_->setObjectName("verdict");
  verdict_label_->setWordWrap(true);

  // One row per candidate of every step: its ΔBIC on the EDC alone and jointly with the response
  // fingerprints, how each piece of evidence moved (Δχ²), and why it was accepted or not.
  step_table_ = new QTableWidget(0, 10);
  step_table_->setHorizontalHeaderLabels(
      {tr("step"), tr("candidate"), tr("outcome"), tr("\u0394BIC joint"), tr("\u0394BIC EDC"),
       tr("\u0394\u03c7\u00b2 EDC"), tr("\u0394\u03c7\u00b2 |Z1|"),
       tr("\u0394\u03c7\u00b2 |Z2|/|Z1|"), tr("\u0394\u03c7\u00b2 |Z3|/|Z1|"), tr("supported by")});
  step_table_->horizontalHeader()->setStretchLastSection(true);
  step_table_->verticalHeader()->hide();
  step_table_->verticalHeader()->setDefaultSectionSize(step_table_->fontMetrics().height() + 6);
  step_table_->setMinimumHeight(180);
  // The σ budget of the final model, per level.
  budget_table_ = new QTableWidget(0, 8);
  budget_table_->setHorizontalHeaderLabels({tr("well"), tr("f0\n[N]"), tr("S_mes\n[mJ]"),
                                            tr("\u03c3 cycles\n[mJ]"), tr("\u03c3 bias\n[mJ]"),
                                            tr("\u03c3 model\n[mJ]"), tr("\u03c3 total\n[mJ]"),
                                            tr("correction\n[mJ]")});
  budget_table_->horizontalHeader()->setStretchLastSection(true);
  budget_table_->verticalHeader()->hide();
  budget_table_->verticalHeader()->setDefaultSectionSize(budget_table_->fontMetrics().height() + 6);
  add_header_tooltips(step_table_);
  add_header_tooltips(budget_table_);
  budget_label_ = new QLabel;
  budget_label_->setWordWrap(true);

  // A page of its own (residual_page()): one panel per well (figures::residual_figure), tall
  // enough for its ticks and legend; a short window scrolls it.
  residual_plot_ = new QCustomPlot;
  residual_plot_->setMinimumHeight(360);
  residual_page_ = new QScrollArea(this);
  residual_page_->setObjectName("residual_page");
  residual_page_->setWidget(residual_plot_);
  residual_page_->setWidgetResizable(true);
  residual_page_->setFrameShape(QFrame::NoFrame);
  // A page of its own (missing_energy_page()): figures::missing_energy_figure.
  missing_energy_plot_ = new QCustomPlot(this);

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(verdict_label_);
  layout->addWidget(step_table_, 1);
  budget_page_ = new QWidget(this);
  auto* budget_layout = new QVBoxLayout(budget_page_);
  budget_layout->addWidget(budget_label_);
  budget_layout->addWidget(budget_table_, 1);
}

QWidget* DiagnosisView::residual_page() const { return residual_page_; }

QWidget* DiagnosisView::missing_energy_page() const { return missing_energy_plot_; }

void DiagnosisView::show_result(const analysis::DiagnosisResult& r, double bic_threshold) {
  verdict_label_->setText(
      tr("<b>Verdict: %1</b> &nbsp; baseline cost %2 mJ (\u03c7\u00b2/\u03bd %3, noise level "
         "%4) \u2192 final %5 mJ (\u03c7\u00b2/\u03bd %6)")
          .arg(QString::fromStdString(r.verdict))
          .arg(1e3 * r.baseline.evaluation.cost_j, 0, 'g', 4)
          .arg(r.baseline_maps.reduced_chi2, 0, 'g', 3)
          .arg(r.noise_reduced_chi2, 0, 'g', 3)
          .arg(1e3 * r.final_evaluation.cost_j, 0, 'g', 4)
          .arg(r.final_maps.reduced_chi2, 0, 'g', 3) +
      gap_text(r) + verdict_details(r));
  show_steps(r, bic_threshold);
  show_residuals(r);
  show_missing_energy(r);
  show_budget(r);
}

void DiagnosisView::show_steps(const analysis::DiagnosisResult& r, double bic_threshold) {
  int rows = 0;
  for (const auto& s : r.steps) rows += static_cast<int>(s.trials.size());
  step_table_->setRowCount(rows);
  int row = 0;
  for (int i = 0; i < static_cast<int>(r.steps.size()); ++i) {
    const auto& s = r.steps[static_cast<std::size_t>(i)];
    for (const auto& t : s.trials) {
      step_table_->setItem(row, 0, read_only_cell(QString::number(i + 1)));
      step_table_->setItem(row, 1,
                           read_only_cell(QString::fromStdString(
                               analysis::candidate_label(t.effect, t.embodiment))));
      step_table_->setItem(
          row, 2,
          read_only_cell(QString::fromStdString(analysis::candidate_outcome(s, t, bic_threshold))));
      step_table_->setItem(
          row, 3, read_only_cell(t.solved ? number_text(t.delta_bic_joint) : QStringLiteral("—")));
      step_table_->setItem(
          row, 4, read_only_cell(t.solved ? number_text(t.delta_bic) : QStringLiteral("—")));
      QString supported;
      for (int column = 5; column < 9; ++column) {
        step_table_->setItem(row, column, read_only_cell("—"));
      }
      for (const auto& e : t.evidence) {
        const int column = e.name == "edc"          ? 5
                           : e.name == "amplitude"  ? 6
                           : e.name == "harmonic-2" ? 7
                                                    : 8;
        step_table_->setItem(row, column, read_only_cell(number_text(e.delta_chi2())));
        if (e.supports()) {
          supported += (supported.isEmpty() ? "" : ", ") + QString::fromStdString(e.name);
        }
      }
      step_table_->setItem(row, 9,
                           read_only_cell(supported.isEmpty() ? QStringLiteral("—") : supported));
      ++row;
    }
  }
  add_cell_tooltips(step_table_);
  step_table_->resizeColumnsToContents();
  // A long outcome or candidate is elided ("…", in full on hover) so that the columns after it
  // stay in view in a narrow panel.
  const int widest_px = step_table_->fontMetrics().horizontalAdvance(QStringLiteral("M")) * 16;
  for (int c = 0; c < step_table_->columnCount() - 1; ++c) {
    step_table_->setColumnWidth(c, std::min(step_table_->columnWidth(c), widest_px));
  }
}

void DiagnosisView::show_residuals(const analysis::DiagnosisResult& r) {
  figures::Figure figure = figures::residual_figure(r);  // the figure of `diagnose`'s residuals.png
  figure.title.clear();                                  // the verdict above says what it is
  render_figure(*residual_plot_, figure);
  residual_plot_->replot();
}

void DiagnosisView::show_missing_energy(const analysis::DiagnosisResult& r) {
  // The figure of `diagnose`'s missing_energy.png; the tab names it and the panel's title says
  // what the slope means.
  figures::Figure figure = figures::missing_energy_figure(r);
  figure.title.clear();
  render_figure(*missing_energy_plot_, figure);
  missing_energy_plot_->replot();
}

void DiagnosisView::show_budget(const analysis::DiagnosisResult& r) {
  const nlohmann::json& b = r.sigma_budget;
  if (!b.is_object() || !b.contains("levels")) {
    budget_table_->setRowCount(0);
    budget_label_->clear();
    return;
  }
  budget_label_->setText(
      tr("Each level's \u03c3\u00b2 = \u03c3_cycles\u00b2 + \u03c3_bias\u00b2 + "
         "\u03c3_model\u00b2 (final model). Harmonic balance at H = %1, corrected to H = %2; "
         "model error |S(%2) \u2212 S(%3)|: %4.")
          .arg(b.value("harmonics", 0))
          .arg(b.value("reference_harmonics", 0))
          .arg(2 * b.value("reference_harmonics", 0) + 1)
          .arg(b.value("resolved", false) ? tr("within target at every level")
                                          : tr("above target at some levels")));
  const auto& levels = b["levels"];
  budget_table_->setRowCount(static_cast<int>(levels.size()));
  int row = 0;
  for (const auto& level : levels) {
    budget_table_->setItem(row, 0, read_only_cell(QString::fromStdString(level.value("well", ""))));
    budget_table_->setItem(row, 1, read_only_cell(number_text(level.value("f0_n", 0.0))));
    const char* keys[] = {"edc_mes_j",     "sigma_cycles_j", "sigma_bias_j",
                          "sigma_model_j", "sigma_j",        "correction_j"};
    for (int column = 2; column < 8; ++column) {
      budget_table_->setItem(
          row, column, read_only_cell(number_text(1e3 * level.value(keys[column - 2], 0.0), 3)));
    }
    ++row;
  }
  add_cell_tooltips(budget_table_);
  budget_table_->resizeColumnsToContents();
}

}  // namespace oscilab::ui
