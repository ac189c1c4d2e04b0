#include "ui/plot_helpers.h"

namespace oscilab::ui {

void set_plot_hint(QCustomPlot* plot, const QString& message) {
  QCPItemText* hint = nullptr;
  for (int i = 0; i < plot->itemCount(); ++i) {
    if (plot->item(i)->objectName() == "hint") hint = qobject_cast<QCPItemText*>(plot->item(i));
  }
  if (!hint) {
    hint = new QCPItemText(plot);
    hint->setObjectName("hint");
    hint->position->setType(QCPItemPosition::ptAxisRectRatio);
    hint->position->setCoords(0.5, 0.5);
    hint->setColor(Qt::gray);
    hint->setClipToAxisRect(false);
  }
  hint->setText(message);
  hint->setVisible(!message.isEmpty());
}

QCPScatterStyle disc_markers(const QColor& colour, double size) {
  return QCPScatterStyle(QCPScatterStyle::ssDisc, colour, colour, size);
}

}  // namespace oscilab::ui
