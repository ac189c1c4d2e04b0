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

QCPTextElement* add_plot_title(QCustomPlot* plot, const QString& title) {
  plot->plotLayout()->insertRow(0);
  QFont font = plot->font();
  font.setBold(true);
  auto* element = new QCPTextElement(plot, title, font);
  plot->plotLayout()->addElement(0, 0, element);
  return element;
}

void frame_axes(QCustomPlot* plot, const QString& x_label, const QString& y_label) {
  plot->xAxis->setLabel(x_label);
  plot->yAxis->setLabel(y_label);
  plot->xAxis->setNumberFormat("gb");
  plot->yAxis->setNumberFormat("gb");
  for (QCPAxis* axis : {plot->xAxis2, plot->yAxis2}) {  // a frame: top and right as lines
    axis->setVisible(true);
    axis->setTicks(false);
    axis->setTickLabels(false);
  }
}

}  // namespace oscilab::ui
