#include "ui/plots/plot_context_menu.h"

#include <QApplication>
#include <QContextMenuEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>

#include <qcustomplot.h>

#include "analysis/common/input_error.h"
#include "ui/plots/plot_export.h"

namespace oscilab::ui {

PlotContextMenus::PlotContextMenus(QObject* parent) : QObject(parent) {
  if (QCoreApplication* app = QCoreApplication::instance()) app->installEventFilter(this);
}

PlotContextMenus::~PlotContextMenus() {
  if (QCoreApplication* app = QCoreApplication::instance()) app->removeEventFilter(this);
}

QCustomPlot* PlotContextMenus::last_hovered() const {
  return qobject_cast<QCustomPlot*>(last_hovered_.data());
}

QMenu* PlotContextMenus::make_menu(QCustomPlot* plot) {
  auto* menu = new QMenu(plot);
  menu->setAttribute(Qt::WA_DeleteOnClose);
  QPointer<QCustomPlot> target(plot);
  menu->addAction(QObject::tr("Export plot\u2026"), plot, [target] {
    if (target) export_plot_interactively(*target, target->window());
  });
  return menu;
}

bool PlotContextMenus::eventFilter(QObject* watched, QEvent* event) {
  // Only two event types matter; everything else passes untouched (this sees every event).
  const QEvent::Type type = event->type();
  if (type != QEvent::ContextMenu && type != QEvent::Enter) return false;
  auto* plot = qobject_cast<QCustomPlot*>(watched);
  if (plot == nullptr) return false;
  if (type == QEvent::Enter) {
    last_hovered_ = plot;
    return false;
  }
  if (plot->contextMenuPolicy() != Qt::DefaultContextMenu) return false;
  last_hovered_ = plot;
  // popup(), not exec(): no nested event loop inside the filter.
  make_menu(plot)->popup(static_cast<QContextMenuEvent*>(event)->globalPos());
  return true;
}

QString export_plot_interactively(QCustomPlot& plot, QWidget* parent) {
  QString filter = QObject::tr("PNG image (*.png)");
  const QString path = QFileDialog::getSaveFileName(
      parent, QObject::tr("Export plot"), plot_file_name(plot) + QStringLiteral(".png"),
      QObject::tr("PNG image (*.png);;SVG drawing (*.svg);;PDF document (*.pdf)"), &filter);
  if (path.isEmpty()) return {};
  QString file = path;
  if (QFileInfo(file).suffix().isEmpty()) {  // the format of the filter chosen
    file += filter.contains("svg") ? ".svg" : filter.contains("pdf") ? ".pdf" : ".png";
  }
  try {
    export_plot(plot, file);
  } catch (const InputError& error) {
    const QString message = QString::fromStdString(error.what());
    QMessageBox::warning(parent, QObject::tr("Export plot"), message);
    return message;
  }
  return {};
}

}  // namespace oscilab::ui
