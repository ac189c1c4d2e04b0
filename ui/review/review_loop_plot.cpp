#include "ui/review/review_loop_plot.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <QFontMetrics>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "analysis/pipeline/result_units.h"
#include "ui/display_units.h"
#include "ui/plots/plot_helpers.h"
#include "ui/plots/plot_theme.h"
#include "ui/plots/well_colours.h"
#include "ui/qt_text.h"
#include "ui/review/review_plot_style.h"

namespace oscilab::ui {
namespace {

// At most this many loops are drawn at once (Fig. 9 overlays two; more become unreadable).
constexpr std::size_t kMaxLoops = 8;
// A legend entry's room besides its icon and text: its margins (QCustomPlot's 8 px a side) and
// the grid's spacing.
constexpr int kLegendEntryPaddingPx = 10;

}  // namespace

ReviewLoopPlot::ReviewLoopPlot() {
  plot_ = make_review_plot(tr("z [mm]"), tr("f = \u2212m d\u00b2b/dt\u00b2 [N]"));
  plot_->setObjectName("loop_plot");
  add_plot_title(plot_, tr("Response-input loops (Fig. 9)"));
  // Row 1: one axis rect per well side by side (each zoomed to its loops, as Fig. 9b/c); row 2:
  // the legend, below them so that it hides no loop.
  QCPAxisRect* first_rect = plot_->axisRect();
  plot_->plotLayout()->take(first_rect);
  grid_ = new QCPLayoutGrid;
  plot_->plotLayout()->addElement(1, 0, grid_);
  grid_->addElement(0, 0, first_rect);
  grid_->setColumnSpacing(4);
  first_rect->insetLayout()->take(plot_->legend);
  plot_->plotLayout()->addElement(2, 0, plot_->legend);
  plot_->plotLayout()->setRowStretchFactor(2, 0.001);
  plot_->legend->setVisible(true);
  plot_->legend->setFillOrder(QCPLayoutGrid::foColumnsFirst);
}

// Curves first (their legend items go with them), then the labels and the extra well rects.
void ReviewLoopPlot::clear() {
  plot_->clearPlottables();
  for (QCPAbstractItem* item : labels_) plot_->removeItem(item);
  labels_.clear();
  for (int c = grid_->columnCount() - 1; c >= 1; --c) {
    if (grid_->element(0, c)) grid_->remove(grid_->element(0, c));
  }
  grid_->simplify();
}

// One axis rect per well present (`present`: positive, negative, other), in that order, each
// with its axis labels and the well's name inside; `rect_of` maps a well's group to its rect.
std::vector<QCPAxisRect*> ReviewLoopPlot::well_rects(const bool present[3],
                                                     const DisplayUnit& z_unit,
                                                     const QString& f_label,
                                                     std::array<QCPAxisRect*, 3>& rect_of) {
  std::vector<QCPAxisRect*> rects;
  for (int g = 0; g < 3; ++g) {
    if (!present[g]) continue;
    QCPAxisRect* rect = rects.empty() ? plot_->axisRect() : new QCPAxisRect(plot_);
    if (!rects.empty()) {
      grid_->addElement(0, int(rects.size()), rect);
      for (QCPAxis::AxisType side : {QCPAxis::atTop, QCPAxis::atRight}) {
        rect->axis(side)->setVisible(true);
        rect->axis(side)->setTicks(false);
        rect->axis(side)->setTickLabels(false);
      }
      rect->axis(QCPAxis::atBottom)->setNumberFormat("gb");
      rect->axis(QCPAxis::atLeft)->setNumberFormat("gb");
      // A rect beside another is narrow: three z ticks, so that "-37.5" and its neighbours do
      // not run into each other (the first rect's ticks follow the plot's width).
      rect->axis(QCPAxis::atBottom)->ticker()->setTickCount(3);
    }
    rect->axis(QCPAxis::atBottom)->setLabel(tr("z [%1]").arg(qtext(z_unit.symbol)));
    rect->axis(QCPAxis::atLeft)->setLabel(rects.empty() ? f_label : QString());
    // The well, top left inside the axes.
    auto* label = new QCPItemText(plot_);
    label->setClipAxisRect(rect);
    label->position->setAxisRect(rect);
    label->position->setType(QCPItemPosition::ptAxisRectRatio);
    label->position->setCoords(0.03, 0.03);
    label->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    label->setText(g == 0   ? tr("around z\u208a*")
                   : g == 1 ? tr("around z\u208b*")
                            : tr("cross-well / unknown"));
    label->setColor(well_colour(g == 0   ? analysis::Well::Positive
                                : g == 1 ? analysis::Well::Negative
                                         : analysis::Well::Unknown));
    draw_legibly(*label);  // the well's colour, legible on a dark theme too
    labels_.push_back(label);
    rect_of[g] = rect;
    rects.push_back(rect);
  }
  return rects;
}

void ReviewLoopPlot::show(const ReviewAnalysis* review, const std::vector<LevelKey>& keys) {
  clear();

  std::vector<LevelLoop> loops;
  std::vector<LevelKey> shown;
  if (review) {
    for (const LevelKey& key : keys) {
      if (loops.size() == kMaxLoops) break;
      const analysis::LevelResult* level = find_level(review->campaign, key);
      if (!level || std::size_t(key.record) >= review->recordings.size()) continue;
      try {
        loops.push_back(level_loop(*review->recordings[std::size_t(key.record)],
                                   review->campaign.settings, *level));
      } catch (const InputError&) {  // the file went away since it was analysed: no loop
        continue;
      }
      shown.push_back(key);
    }
  }
  plot_->legend->setVisible(!loops.empty());
  if (loops.empty()) {
    set_plot_hint(plot_, review ? tr("Select levels in the table to draw their loops")
                                : tr("No analysis yet"));
    plot_->replot(QCustomPlot::rpQueuedReplot);
    return;
  }
  set_plot_hint(plot_, {});
  double z_max = 0.0, f_max = 0.0;
  for (const LevelLoop& loop : loops) {
    z_max = std::max(z_max, largest_abs({&loop.z_m}));
    f_max = std::max(f_max, largest_abs({&loop.f_n}));
  }
  const DisplayUnit z_unit = choose_display_unit("m", z_max);
  const DisplayUnit f_unit = choose_display_unit("N", f_max);
  const bool per_unit_mass =
      review->campaign.records[std::size_t(shown.front().record)].per_unit_mass;
  const QString f_label =
      per_unit_mass ? tr("f / m = \u2212d\u00b2b/dt\u00b2 [%1/kg]").arg(qtext(f_unit.symbol))
                    : tr("f = \u2212m d\u00b2b/dt\u00b2 [%1]").arg(qtext(f_unit.symbol));

  // One axis rect per well, in the order positive, negative, other.
  const auto group_of = [](analysis::Well well) {
    return well == analysis::Well::Positive ? 0 : well == analysis::Well::Negative ? 1 : 2;
  };
  bool present[3] = {false, false, false};
  for (const LevelLoop& loop : loops) present[group_of(loop.well)] = true;
  std::array<QCPAxisRect*, 3> rect_of{};
  const std::vector<QCPAxisRect*> rects = well_rects(present, z_unit, f_label, rect_of);

  // The record's name in the legend only where a well's loops come from more than one record
  // (the rect and the colour say the well).
  bool name_records = false;
  for (std::size_t i = 1; i < loops.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      name_records = name_records || (group_of(loops[i].well) == group_of(loops[j].well) &&
                                      shown[i].record != shown[j].record);
    }
  }
  // The legend's entries (the level table lists their cycles); one entry a row for a few loops,
  // two columns for more when two of the widest fit side by side (set before they are added).
  std::vector<QString> names;
  int widest_px = 0;
  const QFontMetrics metrics(plot_->legend->font());
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const analysis::LevelResult& level = *find_level(review->campaign, shown[i]);
    const analysis::RecordAnalysis& record = review->campaign.records[std::size_t(shown[i].record)];
    names.push_back(tr("%1f\u2080 = %2 %4, EDC %3 %5")
                        .arg(name_records ? qtext(record.name) + QStringLiteral(", ") : QString())
                        .arg(level.f0_n, 0, 'f', 2)
                        .arg(1e3 * level.edc_mean_j, 0, 'f', 3)
                        .arg(qtext(analysis::result_unit("N", record.per_unit_mass)))
                        .arg(qtext(analysis::result_unit("mJ", record.per_unit_mass))));
    widest_px = std::max(widest_px, metrics.horizontalAdvance(names.back()));
  }
  const int entry_px = widest_px + plot_->legend->iconSize().width() +
                       plot_->legend->iconTextPadding() + 2 * kLegendEntryPaddingPx;
  plot_->legend->setWrap(loops.size() > 3 && 2 * entry_px <= plot_->width() ? 2 : 1);
  // Loops drawn so far per well: later ones in shades further from the background (darker on a
  // light one, lighter on a dark one).
  int same_well[3] = {0, 0, 0};
  const bool dark_background = plot_->palette().color(QPalette::Base).lightness() < 128;
  double z_lo[3] = {INFINITY, INFINITY, INFINITY}, z_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double f_lo = INFINITY, f_hi = -INFINITY;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const LevelLoop& loop = loops[i];
    const int g = group_of(loop.well);
    const int shade = 100 + 35 * same_well[g]++;
    const QColor own = well_colour(loop.well);
    const QColor colour = (dark_background ? own.lighter(shade) : own.darker(shade)).toRgb();
    QCPAxisRect* rect = rect_of[g];
    auto* curve = new QCPCurve(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
    QVector<QCPCurveData> data(qsizetype(loop.z_m.size()));
    for (std::size_t k = 0; k < loop.z_m.size(); ++k) {
      const double z = z_unit.to_display(loop.z_m[k]), f = f_unit.to_display(loop.f_n[k]);
      data[qsizetype(k)] = QCPCurveData(double(k), z, f);
      z_lo[g] = std::min(z_lo[g], z);
      z_hi[g] = std::max(z_hi[g], z);
      f_lo = std::min(f_lo, f);
      f_hi = std::max(f_hi, f);
    }
    curve->data()->set(data, true);
    curve->setPen(QPen(colour, 1.2));
    curve->setName(names[i]);
  }
  // Each rect over its loops' z; one force range for all, so that the rects compare. Room at
  // the top (a sixth of the span) for the well's label, whose corner the loops reach.
  for (int g = 0; g < 3; ++g) {
    if (rect_of[g]) fit_axis(rect_of[g]->axis(QCPAxis::atBottom), z_lo[g], z_hi[g]);
  }
  for (QCPAxisRect* rect : rects) {
    fit_axis(rect->axis(QCPAxis::atLeft), f_lo, f_hi + 0.2 * (f_hi - f_lo));
  }
  plot_->replot(QCustomPlot::rpQueuedReplot);
}

}  // namespace oscilab::ui
