#pragma once

#include <array>
#include <vector>

#include <QCoreApplication>

#include "ui/display_units.h"
#include "ui/review/review_model.h"

class QCPAbstractItem;
class QCPAxisRect;
class QCPLayoutGrid;
class QCustomPlot;

namespace oscilab::ui {

/// Fig. 9 of the review: f = −m b̈ against z, one QCPCurve per selected level (at most 8), one
/// axis rect per well side by side, each zoomed to its loops (as Fig. 9b/c), the first the
/// plot's default axisRect(), the legend below them. Shows loops made by review_model.h;
/// computes nothing. UI thread only.
class ReviewLoopPlot {
  Q_DECLARE_TR_FUNCTIONS(ReviewLoopPlot)

 public:
  /// Makes the plot (owned by whoever takes plot()).
  ReviewLoopPlot();

  QCustomPlot* plot() const { return plot_; }
  /// Draws the loops of the levels `keys` of `review` (null: none yet).
  void show(const ReviewAnalysis* review, const std::vector<LevelKey>& keys);

 private:
  void clear();
  std::vector<QCPAxisRect*> well_rects(const bool present[3], const DisplayUnit& z_unit,
                                       const QString& f_label,
                                       std::array<QCPAxisRect*, 3>& rect_of);

  QCustomPlot* plot_ = nullptr;
  QCPLayoutGrid* grid_ = nullptr;         // the axis rects, one per well
  std::vector<QCPAbstractItem*> labels_;  // their well labels
};

}  // namespace oscilab::ui
