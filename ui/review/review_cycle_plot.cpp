#include "ui/review/review_cycle_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <qcustomplot.h>

#include "ui/plots/plot_helpers.h"
#include "ui/plots/plot_theme.h"
#include "ui/plots/well_colours.h"
#include "ui/qt_text.h"
#include "ui/review/review_plot_style.h"
#include "ui/review/time_marks.h"

namespace oscilab::ui {
namespace {}  // namespace

ReviewCyclePlot::ReviewCyclePlot() {
  plot_ = make_review_plot(tr("time [s]"), tr("EDC per cycle [mJ]"));
  plot_->setObjectName("cycle_plot");
  add_plot_title(plot_, tr("Energy dissipated in each fitted cycle (\u00a74.1)"));
  plot_->yAxis->setScaleType(QCPAxis::stLogarithmic);
  plot_->yAxis->setTicker(QSharedPointer<QCPAxisTickerLog>::create());
  plot_->legend->setVisible(true);
  plot_->axisRect()->insetLayout()->setInsetAlignment(0, Qt::AlignBottom | Qt::AlignRight);
  plot_->addLayer("cursor", plot_->layer("main"), QCustomPlot::limAbove);
  plot_->layer("cursor")->setMode(QCPLayer::lmBuffered);
  cursor_ = new QCPItemStraightLine(plot_);
  cursor_->setLayer("cursor");
  cursor_->setPen(QPen(QColor(60, 60, 60), 1.0, Qt::DashLine));
  draw_in_palette_colours(*cursor_);
  cursor_->setVisible(false);
}

void ReviewCyclePlot::set_energy_unit(const QString& unit) {
  plot_->yAxis->setLabel(tr("EDC per cycle [%1]").arg(unit));
}

void ReviewCyclePlot::set_marks(const std::vector<RecordView::Mark>& marks) {
  for (QCPAbstractItem* item : marks_) plot_->removeItem(item);
  marks_.clear();
  for (const RecordView::Mark& mark : marks) {
    add_time_mark(plot_, plot_->axisRect(), mark.t_s, mark.text, marks_);
  }
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

void ReviewCyclePlot::show(const ReviewAnalysis* review, int record_index, bool running,
                           const TimeWindow& window) {
  plot_->clearGraphs();
  const int r = record_index;
  if (r < 0) {
    set_plot_hint(plot_, !review ? (running ? tr("Analysing\u2026") : tr("No analysis yet"))
                                 : tr("The recording shown was not analysed"));
    plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  const analysis::RecordAnalysis& record = review->campaign.records[std::size_t(r)];
  const std::vector<ReviewCycle>& record_cycles = review->cycles[std::size_t(r)];
  if (record_cycles.empty()) {
    set_plot_hint(plot_, tr("No stepped-sine cycles in %1").arg(qtext(record.name)));
    plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(plot_, {});
  // Which level's steady part holds a cycle (its well), if any.
  const auto steady_well = [&](const ReviewCycle& cycle) -> const analysis::Well* {
    for (const analysis::LevelResult& level : record.levels) {
      if (cycle.start_s >= level.start_s - 1e-9 && cycle.end_s <= level.end_s + 1e-9) {
        return &level.well;
      }
    }
    return nullptr;
  };
  QVector<double> other_t, other_e;
  struct WellCycles {
    analysis::Well well;
    QVector<double> t_s, edc_mj;
  };
  std::map<std::string, WellCycles> by_well;  // by the well's name: the legend's order
  for (const ReviewCycle& cycle : record_cycles) {
    const double t_s = 0.5 * (cycle.start_s + cycle.end_s);
    if (const analysis::Well* well = steady_well(cycle)) {
      WellCycles& cycles =
          by_well.try_emplace(to_string(*well), WellCycles{*well, {}, {}}).first->second;
      cycles.t_s.push_back(t_s);
      cycles.edc_mj.push_back(1e3 * cycle.edc_j);
    } else {
      other_t.push_back(t_s);
      other_e.push_back(1e3 * cycle.edc_j);
    }
  }
  QCPGraph* other = plot_->addGraph();
  other->setName(tr("transient or between levels"));
  other->setLineStyle(QCPGraph::lsNone);
  other->setScatterStyle(disc_markers(QColor(160, 160, 160), 3));
  other->setData(other_t, other_e, true);
  for (const auto& [name, cycles] : by_well) {
    QCPGraph* graph = plot_->addGraph();
    graph->setName(tr("steady cycles, %1 well").arg(qtext(name)));
    graph->setLineStyle(QCPGraph::lsNone);
    graph->setScatterStyle(disc_markers(well_colour(cycles.well), 4));
    graph->setData(cycles.t_s, cycles.edc_mj, true);
  }
  // Each level's mean as a segment over its steady part; NaN between levels breaks the line.
  QVector<double> mean_t, mean_e;
  for (const analysis::LevelResult& level : record.levels) {
    if (!mean_t.isEmpty()) {
      mean_t.push_back(0.5 * (mean_t.back() + level.start_s));
      mean_e.push_back(std::numeric_limits<double>::quiet_NaN());
    }
    mean_t << level.start_s << level.end_s;
    mean_e << 1e3 * level.edc_mean_j << 1e3 * level.edc_mean_j;
  }
  QCPGraph* means = plot_->addGraph();
  means->setName(tr("level mean"));
  means->setPen(QPen(Qt::black, 1.5));
  means->setData(mean_t, mean_e, true);
  follow_time_window(window.start_s, window.end_s);
}

void ReviewCyclePlot::follow_time_window(double start_s, double end_s) {
  plot_->xAxis->setRange(start_s, end_s);
  double lo = INFINITY, hi = -INFINITY;
  for (int g = 0; g < plot_->graphCount(); ++g) {
    bool found = false;
    const QCPRange range =
        plot_->graph(g)->getValueRange(found, QCP::sdPositive, QCPRange(start_s, end_s));
    if (!found) continue;
    lo = std::min(lo, range.lower);
    hi = std::max(hi, range.upper);
  }
  // Log axis: a factor 1.3 of room below and above the EDCs in view.
  if (lo <= hi) plot_->yAxis->setRange(lo / 1.3, hi * 1.3);
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

void ReviewCyclePlot::show_cursor(std::optional<double> t_s, bool record_shown) {
  cursor_->setVisible(t_s.has_value() && record_shown);
  if (t_s) {
    cursor_->point1->setCoords(*t_s, 0.0);
    cursor_->point2->setCoords(*t_s, 1.0);
  }
  plot_->layer("cursor")->replot();
}

}  // namespace oscilab::ui
