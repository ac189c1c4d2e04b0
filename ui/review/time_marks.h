#pragma once

#include <vector>

#include <QString>

class QCPAbstractItem;
class QCPAxisRect;
class QCustomPlot;

namespace oscilab::ui {

/// Draws an annotation mark on a time plot: a vertical line at `t_s` across `rect` (whatever its
/// value range) and, when `label` is not empty, the label at the top, right of the line. The
/// items are appended to `items` (so the caller can remove them later). The rect's bottom axis
/// is time in s.
void add_time_mark(QCustomPlot* plot, QCPAxisRect* rect, double t_s, const QString& label,
                   std::vector<QCPAbstractItem*>& items);

}  // namespace oscilab::ui
