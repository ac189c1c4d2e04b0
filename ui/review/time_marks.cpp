#include "ui/review/time_marks.h"

#include <qcustomplot.h>

namespace oscilab::ui {
namespace {

// Annotation marks: a dark violet, apart from the channel and well colours and the grey cursor.
const QColor kMarkColour(0x6a, 0x3d, 0x9a);

// x in the plot's time coordinates, y as a fraction of the axis rect's height (0: top).
void place(QCPItemPosition* position, QCPAxisRect* rect) {
  position->setAxes(rect->axis(QCPAxis::atBottom), rect->axis(QCPAxis::atLeft));
  position->setAxisRect(rect);
  position->setTypeX(QCPItemPosition::ptPlotCoords);
  position->setTypeY(QCPItemPosition::ptAxisRectRatio);
}

}  // namespace

void add_time_mark(QCustomPlot* plot, QCPAxisRect* rect, double t_s, const QString& label,
                   std::vector<QCPAbstractItem*>& items) {
  auto* line = new QCPItemLine(plot);
  line->setClipAxisRect(rect);
  line->setPen(QPen(kMarkColour, 1.2));
  place(line->start, rect);
  place(line->end, rect);
  line->start->setCoords(t_s, 1.0);
  line->end->setCoords(t_s, 0.0);
  items.push_back(line);
  if (label.isEmpty()) return;
  auto* text = new QCPItemText(plot);
  text->setClipAxisRect(rect);
  place(text->position, rect);
  text->position->setCoords(t_s, 0.0);
  text->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
  text->setPadding(QMargins(3, 1, 3, 1));
  text->setText(label);
  text->setColor(kMarkColour);
  text->setBrush(QColor(255, 255, 255, 210));
  items.push_back(text);
}

}  // namespace oscilab::ui
