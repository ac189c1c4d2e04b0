#pragma once

#include <optional>
#include <vector>

#include <QCoreApplication>
#include <QString>

#include "ui/review/record_view.h"
#include "ui/review/review_model.h"

class QCPAbstractItem;
class QCPItemStraightLine;
class QCustomPlot;

namespace oscilab::ui {

/// The review's cycle plot: the EDC of every fitted cycle of the recording shown against time
/// (§4.1), the steady cycles of each level by well, each level's mean over its steady part; a
/// time plot that shows the record view's time window (its log EDC axis the values in it), the
/// shared cursor and the annotations' marks. Shows what the analysis found; computes nothing.
/// UI thread only.
class ReviewCyclePlot {
  Q_DECLARE_TR_FUNCTIONS(ReviewCyclePlot)

 public:
  /// Makes the plot (owned by whoever takes plot()).
  ReviewCyclePlot();

  QCustomPlot* plot() const { return plot_; }
  /// The EDC axis label's unit ("mJ", "mJ/kg").
  void set_energy_unit(const QString& unit);
  /// Draws the cycles of record `record_index` of `review` (-1: the recording shown was not
  /// analysed; null review: none yet, `running` says it is being computed), over `window`.
  void show(const ReviewAnalysis* review, int record_index, bool running, const TimeWindow& window);
  /// Shows [start_s, end_s], the EDC axis over the values in it.
  void follow_time_window(double start_s, double end_s);
  /// The shared cursor at t_s, drawn when there is one and a record is shown.
  void show_cursor(std::optional<double> t_s, bool record_shown);
  /// Replaces the annotations' marks.
  void set_marks(const std::vector<RecordView::Mark>& marks);

 private:
  QCustomPlot* plot_ = nullptr;
  QCPItemStraightLine* cursor_ = nullptr;
  std::vector<QCPAbstractItem*> marks_;
};

}  // namespace oscilab::ui
